#include "models/systems/point_mass_system.hpp"

#include <algorithm>
#include <cmath>

namespace condyn {

namespace {

/// The power of 2 of |x| (1 for 0, inf or NaN): dividing by it is exact, so a computation on x/s
/// rounds as the same computation on x would, where that stays inside the double range.
double power_of_two(double x) {
  return x != 0.0 && std::isfinite(x) ? std::ldexp(1.0, std::ilogb(x)) : 1.0;
}

}  // namespace

double PointMassSystem::distance(const Eigen::VectorXd& d) {
  const double s = power_of_two(d.cwiseAbs().maxCoeff());
  return s * (d / s).norm();
}

PointMassSystem::PointMassSystem(PointMassLayout layout)
    : layout_(std::move(layout)),
      n_(static_cast<int>(layout_.nodes.size()) * layout_.dimension),
      m_(static_cast<int>(layout_.linear_rows.size() + layout_.rods.size())),
      linear_count_(static_cast<int>(layout_.linear_rows.size())),
      linear_(layout_.linear_rows) {
  for (int i = 0; i < linear_count_; ++i) position_.push_back(linear_.is_position(i));
  position_.insert(position_.end(), layout_.rods.size(), true);
  const int dim = layout_.dimension;
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t k = 0; k < layout_.nodes.size(); ++k) {
    for (int d = 0; d < dim; ++d) {
      if (layout_.masses[k] != 0.0) {
        trip.emplace_back(dof(static_cast<int>(k), d), dof(static_cast<int>(k), d),
                          layout_.masses[k]);
      }
    }
  }
  M_.resize(n_, n_);
  M_.setFromTriplets(trip.begin(), trip.end());
  trip.clear();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_);
  std::vector<Eigen::Triplet<double>> c_trip;
  for (const auto& b : layout_.bars) {  // small-displacement stiffness (EA/L) e eᵀ, damping c e eᵀ
    const Eigen::VectorXd d = separation(b, zero);
    const Eigen::VectorXd e = d / distance(d);
    add_block_pair(trip, b, (b.EA / b.length) * e * e.transpose());
    if (b.c != 0.0) add_block_pair(c_trip, b, b.c * e * e.transpose());
    damped_ = damped_ || b.c != 0.0;
  }
  K_linear_.resize(n_, n_);
  K_linear_.setFromTriplets(trip.begin(), trip.end());
  no_damping_.resize(n_, n_);
  damped_ = damped_ || layout_.mass_damping != 0.0;
  C_linear_.resize(n_, n_);
  C_linear_.setFromTriplets(c_trip.begin(), c_trip.end());
  C_linear_ += layout_.mass_damping * M_;
  C_linear_.makeCompressed();
  conservative_ = !damped_;
  for (const auto& l : layout_.loads) conservative_ = conservative_ && l.value.is_constant();
  for (const auto& c : layout_.linear_rows) {
    conservative_ = conservative_ && c.position_value.is_constant();
  }
}

Eigen::VectorXd PointMassSystem::separation(const PointMassLayout::Bar& b,
                                            const ConstRef& u) const {
  const int dim = layout_.dimension;
  Eigen::VectorXd d(dim);
  for (int k = 0; k < dim; ++k) {
    d[k] = layout_.nodes[static_cast<std::size_t>(b.j)][static_cast<std::size_t>(k)] -
           layout_.nodes[static_cast<std::size_t>(b.i)][static_cast<std::size_t>(k)] +
           u[dof(b.j, k)] - u[dof(b.i, k)];
  }
  return d;
}

Eigen::VectorXd PointMassSystem::relative(const PointMassLayout::Bar& b, const ConstRef& v) const {
  const int dim = layout_.dimension;
  Eigen::VectorXd d(dim);
  for (int k = 0; k < dim; ++k) d[k] = v[dof(b.j, k)] - v[dof(b.i, k)];
  return d;
}

void PointMassSystem::add_row_pair(std::vector<Eigen::Triplet<double>>& trip, int row,
                                   const PointMassLayout::Bar& b, const Eigen::VectorXd& r) const {
  for (int k = 0; k < layout_.dimension; ++k) {
    trip.emplace_back(row, dof(b.j, k), r[k]);
    trip.emplace_back(row, dof(b.i, k), -r[k]);
  }
}

void PointMassSystem::add_block_pair(std::vector<Eigen::Triplet<double>>& trip,
                                     const PointMassLayout::Bar& b,
                                     const Eigen::MatrixXd& B) const {
  const int dim = layout_.dimension;
  for (int r = 0; r < dim; ++r) {
    for (int c = 0; c < dim; ++c) {
      trip.emplace_back(dof(b.i, r), dof(b.i, c), B(r, c));
      trip.emplace_back(dof(b.j, r), dof(b.j, c), B(r, c));
      trip.emplace_back(dof(b.i, r), dof(b.j, c), -B(r, c));
      trip.emplace_back(dof(b.j, r), dof(b.i, c), -B(r, c));
    }
  }
}

const MechanicalSystem::Sparse& PointMassSystem::assemble(
    Sparse& S, int rows, int cols, std::vector<Eigen::Triplet<double>>& trip) {
  // The same triplet positions on every call, explicit zeros included: a fixed pattern.
  S.resize(rows, cols);
  S.setFromTriplets(trip.begin(), trip.end());
  S.makeCompressed();
  trip.clear();
  return S;
}

void PointMassSystem::force(double t, ConstRef u, ConstRef v, Ref f) {
  f.setZero();
  for (const auto& l : layout_.loads) l.add_to(f, l.value.derivative(0, t, steps_at(t)));
  if (!layout_.nonlinear_geometry) {
    f.noalias() -= K_linear_ * u;
    if (damped_) f.noalias() -= C_linear_ * v;
    return;
  }
  if (layout_.mass_damping != 0.0) f.noalias() -= layout_.mass_damping * (M_ * v);
  for (const auto& b : layout_.bars) {
    const Eigen::VectorXd d = separation(b, u);
    const double l = distance(d);
    const Eigen::VectorXd e = d / l;
    const double N = b.EA * (l - b.length) / b.length + dashpot_force(b, e, v);
    const Eigen::VectorXd pull = (N / l) * d;  // N e, rounded as before the dashpots
    for (int k = 0; k < layout_.dimension; ++k) {
      f[dof(b.i, k)] += pull[k];
      f[dof(b.j, k)] -= pull[k];
    }
  }
}

const MechanicalSystem::Sparse& PointMassSystem::stiffness(double /*t*/, ConstRef u, ConstRef v) {
  if (!layout_.nonlinear_geometry) {
    return K_linear_;
  }
  const int dim = layout_.dimension;
  for (const auto& b : layout_.bars) {
    const Eigen::VectorXd d = separation(b, u);
    const double l = distance(d);
    const Eigen::VectorXd e = d / l;
    const Eigen::VectorXd w = relative(b, v);
    const double lengthening = e.dot(w);  // l'
    const double N = b.EA * (l - b.length) / b.length + b.c * lengthening;
    Eigen::MatrixXd tangent = (b.EA / b.length) * e * e.transpose() +
                              (N / l) * (Eigen::MatrixXd::Identity(dim, dim) - e * e.transpose());
    // The dashpot's force c l' e turns with the axis (within the N/l term) and changes with
    // l' = e·d', whose derivative along d is (d' − l' e)ᵀ/l.
    if (b.c != 0.0) tangent += (b.c / l) * e * (w - lengthening * e).transpose();
    add_block_pair(trip_, b, tangent);
  }
  return assemble(stiffness_, n_, n_, trip_);
}

const MechanicalSystem::Sparse& PointMassSystem::damping(double /*t*/, ConstRef u, ConstRef /*v*/) {
  if (!damped_) return no_damping_;
  if (!layout_.nonlinear_geometry) return C_linear_;
  // a0 M on the diagonal, c e eᵀ per dashpot on the current axis (every entry kept: a fixed
  // pattern).
  for (int k = 0; k < n_ && layout_.mass_damping != 0.0; ++k) {
    trip_.emplace_back(k, k, layout_.mass_damping * M_.coeff(k, k));
  }
  for (const auto& b : layout_.bars) {
    if (b.c == 0.0) continue;
    const Eigen::VectorXd d = separation(b, u);
    const Eigen::VectorXd e = d / distance(d);
    add_block_pair(trip_, b, b.c * e * e.transpose());
  }
  return assemble(damping_, n_, n_, trip_);
}

const MechanicalSystem::Sparse& PointMassSystem::constraint_jacobian(double /*t*/, ConstRef u) {
  linear_.append_triplets(0, trip_);
  for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
    const auto& b = layout_.rods[r];
    add_row_pair(trip_, linear_count_ + static_cast<int>(r), b, separation(b, u) / b.length);
  }
  return assemble(A_, m_, n_, trip_);
}

void PointMassSystem::position_residual(double t, ConstRef u, Ref phi) {
  linear_.position_residual(t, u, phi.head(linear_count_));
  for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
    const auto& b = layout_.rods[r];
    // (|d|² − L²)/(2L) on d/s and L/s, s a power of 2 of their size: the squares overflowed
    // from |d| ~ 1e154 on (a member of length 1e200 was refused with "residual -nan") and
    // underflowed below 1e-154; the same bits as before where they did not.
    const Eigen::VectorXd d = separation(b, u);
    const double s = power_of_two(std::max(d.cwiseAbs().maxCoeff(), b.length));
    const double length = b.length / s;
    phi[linear_count_ + static_cast<int>(r)] =
        s * (((d / s).squaredNorm() - length * length) / (2.0 * length));
  }
}

void PointMassSystem::velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) {
  linear_.velocity_residual(t, v, psi.head(linear_count_));
  for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
    const auto& b = layout_.rods[r];
    // d·d'/L on d/s and L/s (s the power of 2 of L): d·d' overflowed for a member of 1e300
    // swinging at √(gL); the same bits as before where it did not.
    const double s = power_of_two(b.length);
    psi[linear_count_ + static_cast<int>(r)] =
        (separation(b, u) / s).dot(relative(b, v)) / (b.length / s);
  }
}

void PointMassSystem::acceleration_bias(double t, ConstRef /*u*/, ConstRef v, Ref gamma) {
  linear_.acceleration_bias(t, gamma.head(linear_count_));
  for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
    const auto& b = layout_.rods[r];
    // −|d'|²/L as −|d'/s|²/(L/s²), s the power of 2 of d': no overflow of the squares, the same
    // bits as before where they did not (L/s² leaves the range only where γ does).
    const Eigen::VectorXd w = relative(b, v);
    const double s = power_of_two(w.cwiseAbs().maxCoeff());
    gamma[linear_count_ + static_cast<int>(r)] = -(w / s).squaredNorm() / (b.length / s / s);
  }
}

const MechanicalSystem::Sparse& PointMassSystem::constraint_force_jacobian(double /*t*/,
                                                                           ConstRef /*u*/,
                                                                           ConstRef w) {
  // Aᵀw on the rod rows: ±w_r d/L, so d/du = (w_r/L) [I −I; −I I].
  const int dim = layout_.dimension;
  for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
    const auto& b = layout_.rods[r];
    const double s = w[linear_count_ + static_cast<int>(r)] / b.length;
    add_block_pair(trip_, b, s * Eigen::MatrixXd::Identity(dim, dim));
  }
  return assemble(force_jac_, n_, n_, trip_);
}

const MechanicalSystem::Sparse& PointMassSystem::constraint_product_jacobian(double /*t*/,
                                                                             ConstRef /*u*/,
                                                                             ConstRef a) {
  // (A a)_r = d·(a_j − a_i)/L.
  for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
    const auto& b = layout_.rods[r];
    add_row_pair(trip_, linear_count_ + static_cast<int>(r), b, relative(b, a) / b.length);
  }
  return assemble(product_jac_, m_, n_, trip_);
}

const MechanicalSystem::Sparse& PointMassSystem::velocity_residual_jacobian(double /*t*/,
                                                                            ConstRef /*u*/,
                                                                            ConstRef v) {
  // ψ_r = d·d'/L.
  for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
    const auto& b = layout_.rods[r];
    add_row_pair(trip_, linear_count_ + static_cast<int>(r), b, relative(b, v) / b.length);
  }
  return assemble(psi_jac_, m_, n_, trip_);
}

const MechanicalSystem::Sparse& PointMassSystem::acceleration_bias_jacobian_v(double /*t*/,
                                                                              ConstRef /*u*/,
                                                                              ConstRef v) {
  // γ_r = −|d'|²/L.
  for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
    const auto& b = layout_.rods[r];
    add_row_pair(trip_, linear_count_ + static_cast<int>(r), b, -2.0 * relative(b, v) / b.length);
  }
  return assemble(gamma_jac_v_, m_, n_, trip_);
}

std::optional<double> PointMassSystem::energy(double t, ConstRef u, ConstRef v) {
  if (!conservative_) return std::nullopt;
  return 0.5 * v.dot(M_ * v) + energy_parts(t, u, v)->potential;
}

std::optional<MechanicalSystem::EnergyParts> PointMassSystem::energy_parts(double t, ConstRef u,
                                                                           ConstRef v) {
  EnergyParts parts;
  if (!layout_.nonlinear_geometry) {
    parts.potential = 0.5 * u.dot(K_linear_ * u);
    if (damped_) parts.dissipation_power = v.dot(C_linear_ * v);
  } else {
    parts.dissipation_power = layout_.mass_damping * v.dot(M_ * v);
    for (const auto& b : layout_.bars) {
      const Eigen::VectorXd d = separation(b, u);
      const double l = distance(d);
      const double stretch = l - b.length;  // from the rest length: a pre-stress stores energy
      parts.potential += 0.5 * b.EA / b.length * stretch * stretch;
      if (b.c != 0.0) {  // c l'²
        const double lengthening = (d / l).dot(relative(b, v));
        parts.dissipation_power += b.c * lengthening * lengthening;
      }
    }
  }
  add_load_energy(layout_.loads, t, steps_at(t), u, v, parts.potential, parts.load_power);
  return parts;
}

double PointMassSystem::coordinate_scale() const {
  double scale = 0.0;
  for (const auto& node : layout_.nodes) {
    for (const double x : node) scale = std::max(scale, std::abs(x));
  }
  for (const auto* members : {&layout_.bars, &layout_.rods}) {
    for (const auto& b : *members) scale = std::max(scale, b.length);
  }
  return scale;
}

double PointMassSystem::row_length_scale() const {
  double scale = 0.0;
  for (const auto& b : layout_.rods) scale = std::max(scale, b.length);
  return scale;
}

}  // namespace condyn
