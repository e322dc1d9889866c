// Static condensation of massless directions for the exact modal reference
// (validation/references/static_condensation.hpp).

#include "validation/references/static_condensation.hpp"

#include <algorithm>
#include <sstream>
#include <string>

#include "models/core/eigen_decompositions.hpp"

namespace condyn {
namespace {

/// Relative size below which an eigenvalue of M is zero (M is exact in the models that reach
/// here: zeros of massless DOFs stay zeros to roundoff of the largest mass).
constexpr double kMasslessTolerance = 1e-12;
/// C Z relative to the largest |C| entry below which no damping acts on the massless directions.
constexpr double kDampingTolerance = 1e-12;

std::string text(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// Halves first: S + Sᵀ overflows for entries beyond 9e307 (a mass of 1e308 read as none).
Eigen::MatrixXd symmetric(const Eigen::MatrixXd& S) { return 0.5 * S + 0.5 * S.transpose(); }

}  // namespace

std::optional<StaticCondensation> condense_massless(const LtiSystem& system) {
  const Eigen::Index n = system.M.rows();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> mass(symmetric(system.M));
  if (mass.info() != Eigen::Success) return std::nullopt;  // ModalSolution's checks say why
  const Eigen::VectorXd& mu = mass.eigenvalues();          // ascending
  const double largest = mu.cwiseAbs().maxCoeff();
  Eigen::Index zero = 0;
  while (zero < n && std::abs(mu(zero)) <= kMasslessTolerance * largest) ++zero;
  if (zero == 0) return std::nullopt;
  if (zero == n) throw ExactSolutionUnavailable("the mass matrix is zero: nothing has inertia");
  const Eigen::MatrixXd Z = mass.eigenvectors().leftCols(zero);
  const Eigen::MatrixXd R = mass.eigenvectors().rightCols(n - zero);
  const bool damped = system.C.size() != 0;
  if (damped) {
    const double c_scale = std::max(system.C.cwiseAbs().maxCoeff(), 1e-300);
    const double acting = (system.C * Z).cwiseAbs().maxCoeff();
    if (acting > kDampingTolerance * c_scale) {
      throw ExactSolutionUnavailable(
          "damping acts on the massless directions (|C Z| = " + text(acting) + ", ratio " +
          text(acting / c_scale) +
          " to the largest |C|): they are first order, not static, so static condensation does "
          "not apply");
    }
  }
  const Eigen::MatrixXd kzz = symmetric(Z.transpose() * system.K * Z);
  const Eigen::LLT<Eigen::MatrixXd> hold(kzz);
  if (hold.info() != Eigen::Success || hold.rcond() < 1e-12) {
    throw ExactSolutionUnavailable(
        "stiffness does not hold the massless directions (ZᵀKZ is not positive definite): a "
        "mechanism without mass");
  }
  StaticCondensation c;
  c.T = R - Z * hold.solve(Z.transpose() * system.K * R);
  c.reduced.M = symmetric(R.transpose() * system.M * R);
  c.reduced.K = symmetric(c.T.transpose() * system.K * c.T);
  if (damped) c.reduced.C = symmetric(c.T.transpose() * system.C * c.T);
  for (const auto& f : system.forcing) {
    c.reduced.forcing.push_back({c.T.transpose() * f.b, f.term});
    c.zh.push_back(Z * hold.solve(Z.transpose() * f.b));
    c.terms.push_back(f.term);
  }
  if (system.q0.size() != 0) c.reduced.q0 = R.transpose() * system.q0;
  if (system.v0.size() != 0) c.reduced.v0 = R.transpose() * system.v0;
  return c;
}

LtiState StaticCondensation::expand(const LtiState& x, double t) const {
  LtiState q{T * x.q, T * x.v, T * x.a};
  for (std::size_t j = 0; j < zh.size(); ++j) {
    q.q += zh[j] * terms[j].derivative(0, t);
    q.v += zh[j] * terms[j].derivative(1, t);
    q.a += zh[j] * terms[j].derivative(2, t);
  }
  return q;
}

}  // namespace condyn
