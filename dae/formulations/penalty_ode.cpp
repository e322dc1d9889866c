#include "dae/formulations/penalty_ode.hpp"

#include "dae/linsolve/condensed_newton.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/row_scales.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace condyn {

PenaltyWeights penalty_weights(const Model& model, const SolveSpec& settings) {
  PenaltyWeights p;
  std::ostringstream rule;
  rule.precision(6);
  const double m_max = Eigen::VectorXd(model.M.diagonal()).cwiseAbs().maxCoeff();
  if (settings.penalty_weight) {
    p.position = *settings.penalty_weight;
    rule << "penalty weight w = " << p.position << " from the scene";
  } else {
    const double k_max = Eigen::VectorXd(model.K->diagonal()).cwiseAbs().maxCoeff();
    // A stiffness whose period m_max/k_max is longer than the run holds nothing within it: a
    // weight from it (1e-12 times a unit model's, 2e-6) let a tie drift by 1.5e3 over 100 s.
    // Such a model is weighted as one without stiffness, by its mass and output step.
    const double run = 2.0 * std::numbers::pi / settings.t_end;
    if (k_max > m_max * run * run) {
      p.position = 1e4 * k_max;
      rule << "penalty weight w = " << p.position << " (1e4 x the largest stiffness diagonal)";
    } else {
      const double w = 2.0 * std::numbers::pi / settings.output_step;
      p.position = 1e4 * m_max * w * w;
      rule << "penalty weight w = " << p.position
           << (k_max > 0.0 ? " (stiffness below m (2 pi / t_end)^2, none within the run: "
                           : " (no stiffness: ")
           << "1e4 m (2 pi / output_step)^2)";
    }
  }
  p.velocity = std::sqrt(p.position * m_max);
  rule << ", velocity rows c = " << p.velocity;
  p.rule = rule.str();
  return p;
}

PenaltyOde::PenaltyOde(const MechanicalSystem& system, const PenaltyWeights& weights)
    : system_(system.clone()), weights_(weights), n_(system.dofs()), m_(system.constraints()) {
  if (system.has_curvature()) {
    throw std::invalid_argument(
        "the penalty formulation does not yet support nonlinear constraints");
  }
  force_.resize(n_);
  rows_.resize(m_);
  row_weight_.resize(m_);
  position_mask_.resize(m_, m_);
  velocity_mask_.resize(m_, m_);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_);
  const auto& M = system_->mass(0.0, zero);
  const auto& A = system_->constraint_jacobian(0.0, zero);
  // Row i's spring acts along a_i with stiffness w |a_i|² when its residual a_i·u enters
  // unscaled: a row written as 0.001 u1 = 0.001 u2 got a millionth of the weight and was not
  // held. Each row is weighted by 1/|a_i|², so w is a stiffness whatever the row's scale.
  // |a_i| from the row scaled exactly (models/core/row_scales.hpp): the springs act along the
  // unit normals a_i/|a_i| on the residuals φ_i/|a_i|, and λ_i = w (φ_i/|a_i|)/|a_i| is scaled
  // once at a time (a row at 1e200 got no weight and was not held, one at 1e-160 gave NaN).
  row_scale_ = unit_row_scales(A);
  for (int i = 0; i < m_; ++i) {
    const bool position = system.position_rows()[static_cast<std::size_t>(i)];
    row_weight_[i] = position ? weights.position : weights.velocity;
    (position ? position_mask_ : velocity_mask_).insert(i, i) = 1.0;
  }
  const auto& K0 = system_->stiffness(0.0, zero, zero);
  const auto& C0 = system_->damping(0.0, zero, zero);
  jacobian_ = BlockJacobian(size());
  jacobian_.declare_identity(0, 0, n_);
  jacobian_.declare_identity(0, n_, n_);
  jacobian_.declare(n_, 0, K0);
  jacobian_.declare(n_, n_, C0);
  jacobian_.declare(n_, n_, M);
  const Eigen::SparseMatrix<double> N = normals(A), Nt = N.transpose();
  const Eigen::SparseMatrix<double> AtPA = Nt * position_mask_ * N, AtVA = Nt * velocity_mask_ * N;
  jacobian_.declare(n_, 0, AtPA);
  jacobian_.declare(n_, n_, AtVA);
  jacobian_.finish();
  // The penalized system's matrices (no curvature: constant), and its massless DOFs.
  const Eigen::SparseMatrix<double> K = K0 + weights.position * AtPA,
                                    C = C0 + weights.velocity * AtVA;
  held_ = held_massless(M, C.nonZeros() > 0 ? C : Eigen::SparseMatrix<double>(), K,
                        Eigen::SparseMatrix<double>(0, n_));
}

Eigen::SparseMatrix<double> PenaltyOde::normals(const Eigen::SparseMatrix<double>& A) const {
  return row_scale_.asDiagonal() * A;
}

Eigen::VectorXd PenaltyOde::multipliers(double t, const Eigen::VectorXd& y) const {
  if (m_ == 0) return {};
  Eigen::VectorXd phi(m_), psi(m_);
  system_->position_residual(t, y.head(n_), phi);  // zero on velocity rows
  system_->velocity_residual(t, y.head(n_), y.tail(n_), psi);
  // Along the unit normal first (a length or a speed), then in the row's own units.
  const Eigen::VectorXd along =
      row_scale_.cwiseProduct(position_mask_ * phi + velocity_mask_ * psi);
  return row_weight_.cwiseProduct(row_scale_.cwiseProduct(along));
}

void PenaltyOde::residual(double t, ConstRef y, ConstRef yp, Ref r) const {
  const auto u = y.head(n_), v = y.tail(n_);
  auto& f = force_;
  system_->force(t, u, v, f);
  const auto& M = system_->mass(t, u);
  r.head(n_) = yp.head(n_) - v;
  r.tail(n_) = M * yp.tail(n_) - f;
  if (m_ > 0) {
    const auto& A = system_->constraint_jacobian(t, u);
    r.tail(n_) += A.transpose() * multipliers(t, y);
  }
}

void PenaltyOde::fill_jacobian(double t, ConstRef y, ConstRef /*yp*/, double cj,
                               JacobianMap J) const {
  const auto u = y.head(n_), v = y.tail(n_);
  const auto& M = system_->mass(t, u);
  const auto& K = system_->stiffness(t, u, v);
  const auto& C = system_->damping(t, u, v);
  std::fill_n(J.valuePtr(), J.nonZeros(), 0.0);
  BlockJacobian::add_identity(J, 0, 0, n_, cj);
  BlockJacobian::add_identity(J, 0, n_, n_, -1.0);
  BlockJacobian::add(J, n_, 0, K, 1.0);
  BlockJacobian::add(J, n_, n_, C, 1.0);
  BlockJacobian::add(J, n_, n_, M, cj);
  if (m_ == 0) return;
  const Eigen::SparseMatrix<double> N = normals(system_->constraint_jacobian(t, u)),
                                    Nt = N.transpose();
  BlockJacobian::add(J, n_, 0, Eigen::SparseMatrix<double>(Nt * position_mask_ * N),
                     weights_.position);
  BlockJacobian::add(J, n_, n_, Eigen::SparseMatrix<double>(Nt * velocity_mask_ * N),
                     weights_.velocity);
}

std::unique_ptr<NewtonSystem> PenaltyOde::newton_system() const {
  using Sparse = Eigen::SparseMatrix<double>;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_);
  const Sparse& M = system_->mass(0.0, zero);
  Sparse K = system_->stiffness(0.0, zero, zero);
  Sparse C = system_->damping(0.0, zero, zero);
  if (K.rows() != n_) K.resize(n_, n_);  // no stiffness
  if (C.rows() != n_) C.resize(n_, n_);  // no damping
  if (m_ > 0) {
    const Sparse N = normals(system_->constraint_jacobian(0.0, zero)), Nt = N.transpose();
    K += weights_.position * Sparse(Nt * position_mask_ * N);
    C += weights_.velocity * Sparse(Nt * velocity_mask_ * N);
  }
  return std::make_unique<CondensedNewton>(Scheme::index1, LinearMatrices{M, C, K, Sparse(0, n_)},
                                           Sparse(0, 0));
}

Eigen::VectorXd PenaltyOde::net_force(double t, const Eigen::VectorXd& y) const {
  Eigen::VectorXd f(n_);
  system_->force(t, y.head(n_), y.tail(n_), f);
  if (m_ > 0) {
    const auto& A = system_->constraint_jacobian(t, y.head(n_));
    f -= A.transpose() * multipliers(t, y);
  }
  return f;
}

void PenaltyOde::make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const {
  yp.resize(size());
  if (held_) {
    Eigen::VectorXd u = y.head(n_), v = y.tail(n_);
    const Eigen::VectorXd f = net_force(t, y);
    const Eigen::VectorXd fdot = time_derivative(t, f, [&](double s) { return net_force(s, y); });
    const Eigen::VectorXd a = held_->consistent(f, fdot, u, v);
    y << u, v;
    yp << v, a;
    return;
  }
  const Eigen::VectorXd f = net_force(t, y);
  const auto& M = system_->mass(t, y.head(n_));
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(M);
  if (lu.info() != Eigen::Success) {
    throw std::runtime_error(
        "the penalty formulation needs mass on every DOF: the mass matrix is singular");
  }
  yp.head(n_) = y.tail(n_);
  yp.tail(n_) = lu.solve(f);
}

}  // namespace condyn
