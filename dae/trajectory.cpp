#include "dae/trajectory.hpp"

namespace condyn {

Trajectory assemble_trajectory(const Model& model, const std::vector<double>& times,
                               const std::vector<Eigen::VectorXd>& u,
                               const std::vector<Eigen::VectorXd>& v,
                               const std::vector<Eigen::VectorXd>& a) {
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
  Eigen::LDLT<Eigen::MatrixXd> aat;
  if (m > 0) {
    const Eigen::MatrixXd dense_a(model.A);
    aat.compute(dense_a * dense_a.transpose());
  }
  for (Eigen::Index k = 0; k < nt; ++k) {
    const auto i = static_cast<std::size_t>(k);
    out.u.col(k) = u[i];
    out.v.col(k) = v[i];
    Eigen::VectorXd rho = model.M * a[i] + model.K * u[i] - model.applied_forces(times[i]);
    if (model.has_damping()) rho += model.C * v[i];
    // Report −Aᵀλ rather than rho itself: equal up to roundoff, but exactly zero on DOFs that no
    // constraint touches, and the same definition the multiplier schemes use.
    if (m > 0) {
      out.multiplier.col(k) = -aat.solve(model.A * rho);
      out.reaction.col(k) = -(model.A.transpose() * out.multiplier.col(k));
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
