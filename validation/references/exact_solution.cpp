#include "validation/references/exact_solution.hpp"

#include "dae/formulations/multiplier_recovery.hpp"
#include "dae/interface/interrupt.hpp"

#include "models/core/eigen_decompositions.hpp"
#include "models/core/null_space.hpp"

namespace condyn {

Trajectory exact_trajectory(const Model& model, const std::vector<double>& times) {
  if (model.is_nonlinear()) {
    throw ExactSolutionUnavailable(
        "the model is nonlinear (the modal solution needs constant M, C, K, A)");
  }
  const int n = model.dofs(), m = model.constraint_count();
  if (n > kMaxExactDofs) {
    throw ExactSolutionUnavailable(
        std::to_string(n) +
        " DOFs: the modal solution is dense (a null-space basis and a "
        "generalized eigenproblem of n x n, O(n^3)); it is computed up to " +
        std::to_string(kMaxExactDofs) + " DOFs");
  }
  const Eigen::MatrixXd N = null_space_basis(model.A, n);
  if (N.cols() == 0) {
    throw ExactSolutionUnavailable(
        "the constraints fix every DOF: no modes (the tight reference run follows the rows)");
  }
  Eigen::MatrixXd P(n, m);
  if (m > 0) {
    const Eigen::MatrixXd a(model.A);
    P = a.transpose() * (a * a.transpose()).ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  }
  const Eigen::MatrixXd M(model.M), K(*model.K), C(model.C);
  LtiSystem sys;
  sys.M = N.transpose() * M * N;
  sys.K = N.transpose() * K * N;
  if (model.has_damping()) sys.C = N.transpose() * C * N;
  for (const auto& load : model.loads) {
    // Nᵀ b for the load's vector b (e_dof or a [[load]] pattern).
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    load.add_to(b, 1.0);
    const Eigen::VectorXd projected = N.transpose() * b;
    for (const auto& term : load.value.terms()) sys.forcing.push_back({projected, term});
  }
  for (const auto& c : model.constraints) {
    if (c.position_value.has_record()) {
      // Its pieces are quintics: no closed form is carried here (compare runs a tight reference).
      throw ExactSolutionUnavailable("constraint '" + c.name + "' follows a displacement record (" +
                                     c.position_value.describe() + "): no modal closed form");
    }
  }
  for (int j = 0; j < m; ++j) {
    const Eigen::VectorXd p = P.col(j);
    for (const auto& term : model.constraints[static_cast<std::size_t>(j)].position_value.terms()) {
      if (term.is_zero()) continue;
      const TimeTerm d1 = term.derivative_term(), d2 = d1.derivative_term();
      sys.forcing.push_back({-(N.transpose() * (K * p)), term});
      sys.forcing.push_back({-(N.transpose() * (M * p)), d2});
      if (model.has_damping()) sys.forcing.push_back({-(N.transpose() * (C * p)), d1});
    }
  }
  sys.q0 = N.transpose() * (model.u0 - P * model.position_rhs(0, 0.0));
  sys.v0 = N.transpose() * (model.v0 - P * model.position_rhs(1, 0.0));
  const ModalSolution solution(sys);

  std::vector<Eigen::VectorXd> u, v, lambda;
  const MultiplierRecovery recover(model);
  for (double t : times) {
    check_interrupt();  // every mode at every output time: seconds on large references
    const LtiState s = solution.at(t);
    u.emplace_back(N * s.q);
    v.emplace_back(N * s.v);
    Eigen::VectorXd a = N * s.a;
    if (m > 0) {
      u.back() += P * model.position_rhs(0, t);
      v.back() += P * model.position_rhs(1, t);
      a += P * model.position_rhs(2, t);
    }
    lambda.push_back(recover(t, u.back(), v.back(), a));
  }
  return assemble_trajectory(model, times, u, v, lambda);
}

}  // namespace condyn
