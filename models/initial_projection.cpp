#include "models/initial_projection.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace condyn {

namespace {

constexpr int kMaxIterations = 50;

/// The minimum-norm solution dx of A dx = −r (A with full row rank).
Eigen::VectorXd minimum_norm_step(const Eigen::MatrixXd& A, const Eigen::VectorXd& r) {
  Eigen::LDLT<Eigen::MatrixXd> gram(A * A.transpose());
  const Eigen::VectorXd y = gram.solve(r);
  if (gram.info() != Eigen::Success || !y.allFinite() ||
      gram.vectorD().cwiseAbs().minCoeff() <= 1e-14 * gram.vectorD().cwiseAbs().maxCoeff()) {
    throw std::runtime_error(
        "cannot project the initial state: the constraints are dependent (singular A Aᵀ) there");
  }
  return -A.transpose() * y;
}

}  // namespace

std::string project_initial_state(const MechanicalSystem& system, double t, Eigen::VectorXd& u,
                                  Eigen::VectorXd& v) {
  const int m = system.constraints();
  const Eigen::VectorXd u_in = u, v_in = v;
  std::vector<int> rows;
  for (int i = 0; i < m; ++i) {
    if (system.position_rows()[static_cast<std::size_t>(i)]) rows.push_back(i);
  }
  Eigen::VectorXd all(m);
  int iterations = 0;
  if (!rows.empty()) {
    bool converged = false;
    for (; iterations < kMaxIterations && !converged; ++iterations) {
      const Eigen::MatrixXd A(system.constraint_jacobian(t, u));
      system.position_residual(t, u, all);
      Eigen::MatrixXd Ap(static_cast<Eigen::Index>(rows.size()), A.cols());
      Eigen::VectorXd phi(static_cast<Eigen::Index>(rows.size()));
      for (std::size_t k = 0; k < rows.size(); ++k) {
        Ap.row(static_cast<Eigen::Index>(k)) = A.row(rows[k]);
        phi[static_cast<Eigen::Index>(k)] = all[rows[k]];
      }
      const Eigen::VectorXd du = minimum_norm_step(Ap, phi);
      u += du;
      converged = du.lpNorm<Eigen::Infinity>() <= 1e-14 * (1.0 + u.lpNorm<Eigen::Infinity>());
    }
    if (!converged || !u.allFinite()) {
      std::ostringstream s;
      s << "cannot project the initial state: Gauss-Newton did not converge in " << kMaxIterations
        << " iterations (no configuration near the given one satisfies the constraints)";
      throw std::runtime_error(s.str());
    }
  }
  if (m > 0) {
    system.velocity_residual(t, u, v, all);
    v += minimum_norm_step(Eigen::MatrixXd(system.constraint_jacobian(t, u)), all);
  }
  std::ostringstream s;
  s.precision(3);
  s << "projected the initial state onto the constraints: max |Δu| = "
    << (u - u_in).lpNorm<Eigen::Infinity>()
    << ", max |Δv| = " << (v - v_in).lpNorm<Eigen::Infinity>() << " (" << iterations
    << " Gauss-Newton iterations)";
  return s.str();
}

}  // namespace condyn
