#include "dae/trajectory.hpp"

#include "models/constraint_drift.hpp"

#include <optional>

namespace condyn {

MultiplierRecovery::MultiplierRecovery(const Model& model) : model_(model) {
  if (model.constraint_count() > 0) {
    const Eigen::SparseMatrix<double> At = model.A.transpose();
    aat_.compute(model.A * At);  // m x m, sparse; positive definite (A has full row rank)
  }
}

Eigen::VectorXd MultiplierRecovery::operator()(double t, const Eigen::VectorXd& u,
                                               const Eigen::VectorXd& v,
                                               const Eigen::VectorXd& a) const {
  if (model_.constraint_count() == 0) return {};
  Eigen::VectorXd rho = model_.M * a + model_.K * u - model_.applied_forces(t);
  if (model_.has_damping()) rho += model_.C * v;
  return -aat_.solve(model_.A * rho);
}

Trajectory assemble_trajectory(const Model& model, const std::vector<double>& times,
                               const std::vector<Eigen::VectorXd>& u,
                               const std::vector<Eigen::VectorXd>& v,
                               const std::vector<Eigen::VectorXd>& lambda) {
  const int n = model.dofs(), m = model.constraint_count();
  const auto nt = static_cast<Eigen::Index>(times.size());
  Trajectory out;
  out.t = times;
  out.u.resize(n, nt);
  out.v.resize(n, nt);
  out.reaction.resize(n, nt);
  out.multiplier.resize(m, nt);
  out.drift_position.resize(nt);
  out.drift_velocity.resize(nt);
  const auto evaluator = model.evaluator();
  MechanicalSystem& system = *evaluator;
  ConstraintDrift drift(model);
  const bool conservative = nt > 0 && system.energy(times[0], u[0], v[0]).has_value();
  if (conservative) out.energy.resize(nt);
  for (Eigen::Index k = 0; k < nt; ++k) {
    const auto i = static_cast<std::size_t>(k);
    out.u.col(k) = u[i];
    out.v.col(k) = v[i];
    if (m > 0) {
      out.multiplier.col(k) = lambda[i];
      // Aᵀ(−λ) rather than −(Aᵀλ): exactly +0 on DOFs that no constraint touches (no "-0").
      out.reaction.col(k) = system.constraint_jacobian(times[i], u[i]).transpose() * (-lambda[i]);
    } else {
      out.reaction.col(k).setZero();
    }
    const auto [dp, dv] = drift(times[i], u[i], v[i]);
    out.drift_position[k] = dp;
    out.drift_velocity[k] = dv;
    if (conservative) out.energy[k] = *system.energy(times[i], u[i], v[i]);
  }
  return out;
}

double relative_energy_error(const Model& model, const Trajectory& traj) {
  if (traj.energy.size() == 0) return -1.0;
  const auto evaluator = model.evaluator();
  MechanicalSystem& system = *evaluator;
  double scale = std::abs(traj.energy[0]);
  for (Eigen::Index k = 0; k < traj.energy.size(); ++k) {
    const Eigen::VectorXd v = traj.v.col(k);
    scale = std::max(
        scale, 0.5 * v.dot(system.mass(traj.t[static_cast<std::size_t>(k)], traj.u.col(k)) * v));
  }
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
