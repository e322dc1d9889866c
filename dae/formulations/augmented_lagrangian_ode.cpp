#include "dae/formulations/augmented_lagrangian_ode.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "dae/interface/recoverable_error.hpp"
#include "models/core/row_scales.hpp"

namespace condyn {

namespace {

/// α as a multiple of the largest mass (augmented_lagrangian_parameters() says why).
constexpr double kAlphaPerMass = 1e4;
/// ω in rad per unit time (augmented_lagrangian_parameters() says why).
constexpr double kOmega = 10.0;
/// The iteration stops when a changes by less than this fraction of |a| (max norms): far below
/// any rtol the integrator is given, so that the right-hand side is a function of the state to
/// the integrator's eyes.
constexpr double kSettled = 1e-12;
/// And at the latest after this many solves: a regular row settles in three or four (contraction
/// 1/(1 + α σ̄²/m), about 1e-4 per solve), a mode at σ̄² α / m = 1 (contraction ½) in 40. Modes
/// nearer a singular position stop here: their accelerations are those of the penalty-like
/// regularization this cap leaves, a smooth function of the state (see the header).
constexpr int kMaxIterations = 100;

}  // namespace

AugmentedLagrangianParameters augmented_lagrangian_parameters(const Model& model) {
  AugmentedLagrangianParameters p;
  const auto system = model.system->clone();
  const double m_max =
      Eigen::VectorXd(system->mass(0.0, model.u0).diagonal()).cwiseAbs().maxCoeff();
  p.alpha = kAlphaPerMass * m_max;
  p.xi = 1.0;
  p.omega = kOmega;
  std::ostringstream rule;
  rule.precision(6);
  rule << "augmented Lagrangian (nonlinear model): alpha = " << p.alpha
       << " (1e4 x the largest mass diagonal, on rows of unit gradient), stabilization xi = "
       << p.xi << ", omega = " << p.omega << " rad/s; multipliers iterated to convergence";
  p.rule = rule.str();
  return p;
}

AugmentedLagrangianOde::AugmentedLagrangianOde(const MechanicalSystem& system,
                                               const Eigen::VectorXd& u0,
                                               const AugmentedLagrangianParameters& parameters)
    : system_(system.clone()),
      observer_(system.clone()),
      parameters_(parameters),
      n_(system.dofs()),
      m_(system.constraints()) {
  row_scale_ = unit_row_scales(system_->constraint_jacobian(0.0, u0));
  try {
    factor(*system_, 0.0, u0);
  } catch (const RecoverableError& e) {
    throw std::invalid_argument(std::string("augmented Lagrangian: ") + e.what() +
                                " at the initial state");
  }
}

void AugmentedLagrangianOde::factor(MechanicalSystem& system, double t, const ConstRef& u) const {
  const Eigen::SparseMatrix<double> A = row_scale_.asDiagonal() * system.constraint_jacobian(t, u);
  const Eigen::SparseMatrix<double> S =
      system.mass(t, u) + parameters_.alpha * Eigen::SparseMatrix<double>(A.transpose() * A);
  if (!analysed_) {
    factor_.analyzePattern(S);  // the patterns of M and A do not depend on the state
    analysed_ = true;
  }
  factor_.factorize(S);
  if (factor_.info() != Eigen::Success || (factor_.vectorD().array() <= 0.0).any()) {
    throw RecoverableError(
        "M + A^T alpha A is not positive definite (a DOF with neither mass nor a constraint)");
  }
  scaled_a_ = A;
}

AugmentedLagrangianOde::Solution AugmentedLagrangianOde::solve(MechanicalSystem& system, double t,
                                                               const ConstRef& u, const ConstRef& v,
                                                               Eigen::VectorXd& lambda) const {
  factor(system, t, u);
  const Eigen::SparseMatrix<double>& A = scaled_a_;
  Eigen::VectorXd f(n_), phi(m_), psi(m_), gamma(m_);
  system.force(t, u, v, f);
  system.position_residual(t, u, phi);  // zero on velocity rows
  system.velocity_residual(t, u, v, psi);
  system.acceleration_bias(t, u, v, gamma);
  const double xi = parameters_.xi, omega = parameters_.omega, alpha = parameters_.alpha;
  // What A a must cancel: the acceleration form with the critically damped stabilization.
  const Eigen::VectorXd r =
      row_scale_.cwiseProduct(-gamma + 2.0 * xi * omega * psi + omega * omega * phi);
  const Eigen::VectorXd base = f - alpha * (A.transpose() * r);
  Solution s;
  s.a = factor_.solve(base - A.transpose() * lambda);
  lambda += alpha * (A * s.a + r);
  double scale = s.a.lpNorm<Eigen::Infinity>();  // the largest |a| of the iterates
  for (int k = 1; k < kMaxIterations; ++k) {
    const Eigen::VectorXd a = factor_.solve(base - A.transpose() * lambda);
    lambda += alpha * (A * a + r);
    const double change = (a - s.a).lpNorm<Eigen::Infinity>();
    s.a = a;
    if (!s.a.allFinite()) throw RecoverableError("augmented Lagrangian: non-finite accelerations");
    scale = std::max(scale, s.a.lpNorm<Eigen::Infinity>());
    if (change <= kSettled * scale) {
      s.lambda = row_scale_.cwiseProduct(lambda);
      return s;
    }
  }
  s.lambda = row_scale_.cwiseProduct(lambda);
  return s;
}

void AugmentedLagrangianOde::rhs(double t, ConstRef y, Ref ydot) const {
  const auto u = y.head(n_), v = y.tail(n_);
  ydot.head(n_) = v;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m_);
  ydot.tail(n_) = solve(*system_, t, u, v, lambda).a;
}

Eigen::VectorXd AugmentedLagrangianOde::multipliers(double t, const Eigen::VectorXd& y) const {
  if (m_ == 0) return {};
  // From zero, not from the run's last: an output's λ must not depend on the evaluations before.
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m_);
  return solve(*observer_, t, y.head(n_), y.tail(n_), lambda).lambda;
}

}  // namespace condyn
