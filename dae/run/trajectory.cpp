#include "dae/run/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace condyn {

RowAssembler::RowAssembler(const Model& model, bool accelerations, bool energy_balance)
    : model_(model), system_(model.evaluator()), drift_(model), held_(held_massless_of(model)) {
  if (accelerations) acceleration_.emplace(model, held_);
  if (energy_balance) energy_.emplace(model);
}

TrajectoryRow RowAssembler::operator()(double t, Eigen::VectorXd u, Eigen::VectorXd v,
                                       Eigen::VectorXd lambda, const Eigen::VectorXd& integrals) {
  TrajectoryRow row;
  row.t = t;
  if (held_) held_->settle(model_.applied_forces(t), model_.applied_forces_derivative(1, t), u, v);
  if (model_.constraint_count() > 0) {
    // Aᵀ(−λ) rather than −(Aᵀλ): exactly +0 on DOFs that no constraint touches (no "-0").
    row.reaction = system_->constraint_jacobian(t, u).transpose() * (-lambda);
  } else {
    row.reaction = Eigen::VectorXd::Zero(u.size());
  }
  if (acceleration_) row.acceleration = (*acceleration_)(*system_, t, u, v, row.reaction);
  const auto [dp, dv] = drift_(t, u, v);
  row.drift_position = dp;
  row.drift_velocity = dv;
  const auto energy = system_->energy(t, u, v);
  if (!conservative_) conservative_ = energy.has_value();
  if (*conservative_ && energy) {
    row.conservative = true;
    row.energy = *energy;
    row.kinetic = 0.5 * v.dot(system_->mass(t, u) * v);
    if (!energy_scale_) energy_scale_ = model_energy_scale(model_, *system_, t, u, v);
    row.energy_scale = *energy_scale_;
  }
  if (energy_) {
    row.balance = energy_->at(t, u, v, integrals);
    if (!initial_energy_) initial_energy_ = row.balance->energy();
    row.balance->initial = *initial_energy_;
  }
  row.u = std::move(u);
  row.v = std::move(v);
  row.multiplier = std::move(lambda);
  return row;
}

void RowLog::add(const TrajectoryRow& row) {
  t_.push_back(row.t);
  if (row.u.size() > 0) max_abs_u_ = std::max(max_abs_u_, row.u.cwiseAbs().maxCoeff());
  drift_position_.push_back(row.drift_position);
  drift_velocity_.push_back(row.drift_velocity);
  near_singular_.push_back(row.near_singular);
  if (row.conservative) {
    energy_.push_back(row.energy);
    kinetic_.push_back(row.kinetic);
    energy_scale_ = std::max(energy_scale_, row.energy_scale);
  }
  if (row.balance) balance_.push_back(*row.balance);
}

Trajectory RowLog::trajectory() const {
  const auto vector = [](const std::vector<double>& x) {
    return Eigen::VectorXd(
        Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size())));
  };
  Trajectory out;
  out.t = t_;
  out.drift_position = vector(drift_position_);
  out.drift_velocity = vector(drift_velocity_);
  out.energy = vector(energy_);
  out.kinetic = vector(kinetic_);
  out.energy_scale = energy_scale_;
  out.balance = balance_;
  out.near_singular = near_singular_;
  return out;
}

TrajectoryRow row_of(const Trajectory& traj, Eigen::Index k) {
  const auto i = static_cast<std::size_t>(k);
  const auto column = [k](const Eigen::MatrixXd& x) {
    return x.cols() > k ? Eigen::VectorXd(x.col(k)) : Eigen::VectorXd();
  };
  const auto entry = [k](const Eigen::VectorXd& x) { return x.size() > k ? x[k] : 0.0; };
  TrajectoryRow row;
  row.t = traj.t.at(i);
  row.u = column(traj.u);
  row.v = column(traj.v);
  row.reaction = column(traj.reaction);
  row.multiplier = column(traj.multiplier);
  row.acceleration = column(traj.acceleration);
  row.drift_position = entry(traj.drift_position);
  row.drift_velocity = entry(traj.drift_velocity);
  row.conservative = traj.energy.size() > k;
  row.energy = entry(traj.energy);
  row.kinetic = entry(traj.kinetic);
  row.energy_scale = traj.energy_scale;
  if (traj.balance.size() > i) row.balance = traj.balance[i];
  row.near_singular = traj.near_singular.size() > i && traj.near_singular[i];
  return row;
}

Trajectory trajectory_of(const TrajectoryRow& row) {
  RowLog log;
  log.add(row);
  Trajectory out = log.trajectory();
  out.u = row.u;
  out.v = row.v;
  out.reaction = row.reaction;
  out.multiplier = row.multiplier;
  if (row.acceleration.size() > 0) out.acceleration = row.acceleration;
  return out;
}

Trajectory assemble_trajectory(const Model& model, const std::vector<double>& times,
                               const std::vector<Eigen::VectorXd>& u,
                               const std::vector<Eigen::VectorXd>& v,
                               const std::vector<Eigen::VectorXd>& lambda, bool accelerations,
                               const std::vector<Eigen::VectorXd>& integrals) {
  const int n = model.dofs(), m = model.constraint_count();
  const auto nt = static_cast<Eigen::Index>(times.size());
  Trajectory out;
  out.u.resize(n, nt);
  out.v.resize(n, nt);
  out.reaction.resize(n, nt);
  out.multiplier.resize(m, nt);
  if (accelerations) out.acceleration.resize(n, nt);
  out.t.reserve(times.size());
  const bool balance = !integrals.empty();
  RowAssembler assemble(model, accelerations, balance);
  for (Eigen::Index k = 0; k < nt; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const TrajectoryRow row = assemble(times[i], u[i], v[i], m > 0 ? lambda[i] : Eigen::VectorXd(),
                                       balance ? integrals[i] : Eigen::VectorXd());
    out.t.push_back(row.t);
    out.u.col(k) = row.u;
    out.v.col(k) = row.v;
    out.reaction.col(k) = row.reaction;
    if (accelerations) out.acceleration.col(k) = row.acceleration;
    if (m > 0) out.multiplier.col(k) = row.multiplier;
    const auto grow = [k](Eigen::VectorXd& x, Eigen::Index size, double value) {
      if (x.size() != size) x.resize(size);
      x[k] = value;
    };
    grow(out.drift_position, nt, row.drift_position);
    grow(out.drift_velocity, nt, row.drift_velocity);
    if (row.conservative) {
      grow(out.energy, nt, row.energy);
      grow(out.kinetic, nt, row.kinetic);
      out.energy_scale = std::max(out.energy_scale, row.energy_scale);
    }
    if (row.balance) out.balance.push_back(*row.balance);
  }
  return out;
}

double model_energy_scale(const Model& model, MechanicalSystem& system, double t,
                          const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(u.size());
  system.force(t, u, v, f);
  // A linear model starting at its static equilibrium has f = f_ext − K u = 0: its loads count.
  const double force = std::max(f.lpNorm<1>(), model.applied_forces(t).lpNorm<1>());
  const double size = std::max(system.coordinate_scale(), u.lpNorm<Eigen::Infinity>());
  const double scale = force * size;
  return std::isfinite(scale) ? scale : 0.0;
}

double energy_error_scale(const Trajectory& traj) {
  if (traj.energy.size() == 0) return 0.0;
  double scale = std::max(std::abs(traj.energy[0]), traj.energy_scale);
  if (traj.kinetic.size() > 0) scale = std::max(scale, traj.kinetic.maxCoeff());
  return scale;
}

double relative_energy_error(const Trajectory& traj) {
  if (traj.energy.size() == 0) return -1.0;
  // An energy beyond the double range (a load of 1e200 times its displacement) made
  // inf - inf: the figure read 0.
  if (!traj.energy.allFinite() || !traj.kinetic.allFinite()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const double scale = energy_error_scale(traj);
  const double worst = (traj.energy.array() - traj.energy[0]).abs().maxCoeff();
  return scale > 0.0 ? worst / scale : worst;
}

long VelocityReversals::operator()(const Eigen::Ref<const Eigen::VectorXd>& v) {
  if (last_.size() != v.size()) {
    last_ = Eigen::VectorXd::Zero(v.size());
    peak_ = Eigen::VectorXd::Zero(v.size());
    count_ = Eigen::Matrix<long, Eigen::Dynamic, 1>::Zero(v.size());
  }
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    constexpr double kDeadBand = 1e-3;
    peak_[i] = std::max(peak_[i], std::abs(v[i]));
    if (std::abs(v[i]) <= kDeadBand * peak_[i]) continue;
    if (last_[i] != 0.0 && (v[i] > 0.0) != (last_[i] > 0.0)) most_ = std::max(most_, ++count_[i]);
    last_[i] = v[i];
  }
  return most_;
}

}  // namespace condyn
