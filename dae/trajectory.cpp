#include "dae/trajectory.hpp"

namespace condyn {

MultiplierRecovery::MultiplierRecovery(const Model& model) : model_(model) {
  if (model.constraint_count() > 0) {
    const Eigen::MatrixXd a(model.A);
    aat_.compute(a * a.transpose());
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
  for (Eigen::Index k = 0; k < nt; ++k) {
    const auto i = static_cast<std::size_t>(k);
    out.u.col(k) = u[i];
    out.v.col(k) = v[i];
    if (m > 0) {
      out.multiplier.col(k) = lambda[i];
      // Aᵀ(−λ) rather than −(Aᵀλ): exactly +0 on DOFs that no constraint touches (no "-0").
      out.reaction.col(k) = model.A.transpose() * (-lambda[i]);
    } else {
      out.reaction.col(k).setZero();
    }
    const auto [dp, dv] = model.drift(times[i], u[i], v[i]);
    out.drift_position[k] = dp;
    out.drift_velocity[k] = dv;
  }
  return out;
}

}  // namespace condyn
