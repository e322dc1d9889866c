#include "dae/linsolve/velocity_jump.hpp"

#include "dae/linsolve/kkt.hpp"

namespace condyn {

void jump_onto_velocity_rows(MechanicalSystem& system, double t, const Eigen::VectorXd& u,
                             Eigen::VectorXd& v) {
  const int n = system.dofs(), m = system.constraints();
  if (m == 0 || !system.has_curvature()) return;
  Eigen::VectorXd psi(m);
  system.velocity_residual(t, u, v, psi);
  KktLu lu;
  lu.compute(kkt_matrix(system.mass(t, u), system.constraint_jacobian(t, u)));
  if (lu.info() != Eigen::Success) return;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  rhs.tail(m) = -psi;
  v += lu.solve(rhs).head(n);
}

}  // namespace condyn
