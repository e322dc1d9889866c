#pragma once
// Fixtures of the modal solver's tests (tests/validation/test_modal_exact*.cpp): time-function
// terms, small LTI systems, the equation residual, and the tolerances with their reasons.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "validation/references/modal_exact.hpp"

namespace condyn::test::modal {

using condyn::DividedDifference;
using condyn::ExactSolutionUnavailable;
using condyn::exp_divided_difference;
using condyn::LtiState;
using condyn::LtiSystem;
using condyn::ModalSolution;
using condyn::TimeTerm;
using Complex = std::complex<double>;

inline constexpr double kEps = std::numeric_limits<double>::epsilon();
// Well-separated points: the explicit formula and Opitz' matrix agree to rounding, a few ulps per
// operation of a 3 x 3 exponential: 64 eps (observed up to 4.4e-16).
inline constexpr double kDividedDifferenceTolerance = 64 * kEps;
// Step for central differences in t.
inline constexpr double kFiniteDifferenceStep = 1e-4;
// Central difference truncation error h^2 f'''/6 with f''' = O(1), plus rounding eps/h.
inline constexpr double kFiniteDifferenceTolerance = 1e-7;
// Rounding of the exponentials grows like eps ||tZ||, the condition number of exp at a normal tZ
// (Higham, Functions of Matrices, SIAM 2008, §10.2), with ||tZ|| up to ~100 here; 32 of those for
// the modal transform and the sums around it.
inline constexpr double kExponentialRoundoff = 32 * kEps * 100.0;
// Single-DOF responses against closed forms, relative to the response scale (observed up to
// 1.7e-14).
inline constexpr double kClosedFormTolerance = kExponentialRoundoff;
// Relative residual of the equation of motion: rounding in the modal transform and exponentials
// (observed up to 7.1e-15).
inline constexpr double kResidualTolerance = kExponentialRoundoff;
// Natural frequencies quoted to six decimals in the reference document.
inline constexpr double kQuotedFrequencyTolerance = 1e-6;
// Static limit after ~30 e-foldings of the slowest mode's decay: the transient left, e^-33 ≈ 5e-15
// of the initial amplitude, is below the exponentials' rounding (observed 1.1e-14 relative).
inline constexpr double kStaticLimitTolerance = kExponentialRoundoff;

inline TimeTerm step(double amplitude, double start = 0.0) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::step;
  term.amplitude = amplitude;
  term.start = start;
  return term;
}

inline TimeTerm polynomial(std::vector<double> coefficients) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::polynomial;
  term.coefficients = std::move(coefficients);
  return term;
}

inline TimeTerm harmonic(double amplitude, double omega, double phase = 0.0) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::harmonic;
  term.amplitude = amplitude;
  term.omega = omega;
  term.phase = phase;
  return term;
}

inline TimeTerm exponential(double amplitude, double rate) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::exponential;
  term.amplitude = amplitude;
  term.rate = rate;
  return term;
}

inline Eigen::MatrixXd scalar(double v) { return Eigen::MatrixXd::Constant(1, 1, v); }

/// Single DOF m x'' + c x' + k x = term(t), x(0) = x0, x'(0) = v0.
inline LtiSystem single_dof(double m, double c, double k, const TimeTerm& term, double x0 = 0.0,
                            double v0 = 0.0) {
  LtiSystem s;
  s.M = scalar(m);
  if (c != 0.0) s.C = scalar(c);
  s.K = scalar(k);
  s.forcing.push_back({Eigen::VectorXd::Ones(1), term});
  s.q0 = Eigen::VectorXd::Constant(1, x0);
  s.v0 = Eigen::VectorXd::Constant(1, v0);
  return s;
}

inline double relative_error(double actual, double expected, double scale) {
  return std::abs(actual - expected) / scale;
}

/// Relative residual of M a + C v + K q = sum_j b_j tau_j(t).
inline double equation_residual(const LtiSystem& s, const LtiState& state, double t) {
  Eigen::VectorXd load = Eigen::VectorXd::Zero(s.M.rows());
  for (const auto& f : s.forcing) load += f.b * f.term.value(t);
  const Eigen::VectorXd inertia = s.M * state.a;
  const Eigen::VectorXd elastic = s.K * state.q;
  Eigen::VectorXd damping = Eigen::VectorXd::Zero(s.M.rows());
  if (s.C.size() != 0) damping = s.C * state.v;
  const double scale =
      std::max({inertia.lpNorm<Eigen::Infinity>(), elastic.lpNorm<Eigen::Infinity>(),
                damping.lpNorm<Eigen::Infinity>(), load.lpNorm<Eigen::Infinity>(), 1e-300});
  return (inertia + damping + elastic - load).lpNorm<Eigen::Infinity>() / scale;
}

inline LtiSystem three_dof() {
  LtiSystem s;
  s.M = Eigen::Vector3d(3.0, 4.0, 4.0).asDiagonal();
  s.K.resize(3, 3);
  s.K << 10, 0, 0, 0, 10, 10, 0, 10, 15;
  s.forcing.push_back({Eigen::Vector3d(0.0, 2.0, 1.0), step(1.0)});
  s.q0 = Eigen::VectorXd::Zero(3);
  s.v0 = Eigen::VectorXd::Zero(3);
  return s;
}

}  // namespace condyn::test::modal
