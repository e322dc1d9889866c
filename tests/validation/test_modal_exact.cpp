#include "validation/modal_exact.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

namespace {

using condyn::DividedDifference;
using condyn::ExactSolutionUnavailable;
using condyn::exp_divided_difference;
using condyn::LtiForcing;
using condyn::LtiState;
using condyn::LtiSystem;
using condyn::ModalSolution;
using condyn::TimeTerm;
using Complex = std::complex<double>;

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Well-separated points: the explicit formula and Opitz' matrix agree to rounding, a few ulps per
// operation of a 3 x 3 exponential: 64 eps (observed up to 4.4e-16).
constexpr double kDividedDifferenceTolerance = 64 * kEps;
// Step for central differences in t.
constexpr double kFiniteDifferenceStep = 1e-4;
// Central difference truncation error h^2 f'''/6 with f''' = O(1), plus rounding eps/h.
constexpr double kFiniteDifferenceTolerance = 1e-7;
// Rounding of the exponentials grows like eps ||tZ||, the condition number of exp at a normal tZ
// (Higham, Functions of Matrices, SIAM 2008, §10.2), with ||tZ|| up to ~100 here; 32 of those for
// the modal transform and the sums around it.
constexpr double kExponentialRoundoff = 32 * kEps * 100.0;
// Single-DOF responses against closed forms, relative to the response scale (observed up to
// 1.7e-14).
constexpr double kClosedFormTolerance = kExponentialRoundoff;
// Relative residual of the equation of motion: rounding in the modal transform and exponentials
// (observed up to 7.1e-15).
constexpr double kResidualTolerance = kExponentialRoundoff;
// Natural frequencies quoted to six decimals in the reference document.
constexpr double kQuotedFrequencyTolerance = 1e-6;
// Static limit after ~30 e-foldings of the slowest mode's decay: the transient left, e^-33 ≈ 5e-15
// of the initial amplitude, is below the exponentials' rounding (observed 1.1e-14 relative).
constexpr double kStaticLimitTolerance = kExponentialRoundoff;

TimeTerm step(double amplitude, double start = 0.0) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::step;
  term.amplitude = amplitude;
  term.start = start;
  return term;
}

TimeTerm polynomial(std::vector<double> coefficients) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::polynomial;
  term.coefficients = std::move(coefficients);
  return term;
}

TimeTerm harmonic(double amplitude, double omega, double phase = 0.0) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::harmonic;
  term.amplitude = amplitude;
  term.omega = omega;
  term.phase = phase;
  return term;
}

TimeTerm exponential(double amplitude, double rate) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::exponential;
  term.amplitude = amplitude;
  term.rate = rate;
  return term;
}

Eigen::MatrixXd scalar(double v) { return Eigen::MatrixXd::Constant(1, 1, v); }

/// Single DOF m x'' + c x' + k x = term(t), x(0) = x0, x'(0) = v0.
LtiSystem single_dof(double m, double c, double k, const TimeTerm& term, double x0 = 0.0,
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

double relative_error(double actual, double expected, double scale) {
  return std::abs(actual - expected) / scale;
}

/// Relative residual of M a + C v + K q = sum_j b_j tau_j(t).
double equation_residual(const LtiSystem& s, const LtiState& state, double t) {
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

LtiSystem three_dof() {
  LtiSystem s;
  s.M = Eigen::Vector3d(3.0, 4.0, 4.0).asDiagonal();
  s.K.resize(3, 3);
  s.K << 10, 0, 0, 0, 10, 10, 0, 10, 15;
  s.forcing.push_back({Eigen::Vector3d(0.0, 2.0, 1.0), step(1.0)});
  s.q0 = Eigen::VectorXd::Zero(3);
  s.v0 = Eigen::VectorXd::Zero(3);
  return s;
}

}  // namespace

TEST_CASE("exp_divided_difference matches the explicit formula for distinct points") {
  const Complex z0(-0.3, 1.0), z1(0.5, -0.2), z2(-1.1, 0.0);
  for (double t : {0.7, 2.0}) {
    CAPTURE(t);
    const Complex e0 = std::exp(z0 * t), e1 = std::exp(z1 * t), e2 = std::exp(z2 * t);

    const DividedDifference single = exp_divided_difference({z0}, t);
    CHECK(std::abs(single.value - e0) < kDividedDifferenceTolerance * std::abs(e0));

    const Complex two = (e0 - e1) / (z0 - z1);
    const DividedDifference d2 = exp_divided_difference({z0, z1}, t);
    CHECK(std::abs(d2.value - two) < kDividedDifferenceTolerance * std::abs(two));

    const Complex three =
        e0 / ((z0 - z1) * (z0 - z2)) + e1 / ((z1 - z0) * (z1 - z2)) + e2 / ((z2 - z0) * (z2 - z1));
    const DividedDifference d3 = exp_divided_difference({z0, z1, z2}, t);
    CHECK(std::abs(d3.value - three) < kDividedDifferenceTolerance * std::abs(three));
    // Symmetric in its points.
    const DividedDifference d3r = exp_divided_difference({z2, z0, z1}, t);
    CHECK(std::abs(d3r.value - three) < kDividedDifferenceTolerance * std::abs(three));
  }
}

TEST_CASE("exp_divided_difference has the confluent limits") {
  const Complex z(-0.4, 1.3);
  const double t = 1.7;
  const Complex e = std::exp(z * t);
  const DividedDifference two = exp_divided_difference({z, z}, t);
  CHECK(std::abs(two.value - t * e) < kDividedDifferenceTolerance * std::abs(t * e));
  const DividedDifference three = exp_divided_difference({z, z, z}, t);
  const Complex expected = 0.5 * t * t * e;
  CHECK(std::abs(three.value - expected) < kDividedDifferenceTolerance * std::abs(expected));
  // Four zeros: t^3 / 3!.
  const DividedDifference zeros = exp_divided_difference({0.0, 0.0, 0.0, 0.0}, t);
  CHECK(std::abs(zeros.value - t * t * t / 6.0) < kDividedDifferenceTolerance);
}

TEST_CASE("exp_divided_difference time derivatives match central differences") {
  const std::vector<std::vector<Complex>> point_sets = {
      {Complex(-0.3, 1.0)},
      {Complex(-0.3, 1.0), Complex(0.5, -0.2)},
      {Complex(0.0), Complex(-0.2, 0.9), Complex(-0.2, -0.9)},
      {Complex(0.0, 2.0), Complex(0.0, 2.0), Complex(0.0, -2.0)},
  };
  const double h = kFiniteDifferenceStep;
  for (const auto& z : point_sets) {
    for (double t : {0.5, 3.0}) {
      CAPTURE(z.size());
      CAPTURE(t);
      const DividedDifference mid = exp_divided_difference(z, t);
      const DividedDifference plus = exp_divided_difference(z, t + h);
      const DividedDifference minus = exp_divided_difference(z, t - h);
      const Complex fd1 = (plus.value - minus.value) / (2.0 * h);
      const Complex fd2 = (plus.value - 2.0 * mid.value + minus.value) / (h * h);
      const Complex fd2_from_d1 = (plus.d1 - minus.d1) / (2.0 * h);
      CHECK(std::abs(mid.d1 - fd1) < kFiniteDifferenceTolerance);
      CHECK(std::abs(mid.d2 - fd2_from_d1) < kFiniteDifferenceTolerance);
      // Second difference of the value loses eps/h^2 ~ 1e-8 to rounding.
      CHECK(std::abs(mid.d2 - fd2) < 100 * kFiniteDifferenceTolerance);
    }
  }
}

TEST_CASE("exp_divided_difference at t = 0 is the identity column") {
  const Complex a(-0.5, 2.0), b(1.5, 0.0), c(0.3, -0.7);
  const DividedDifference one = exp_divided_difference({a}, 0.0);
  CHECK(one.value == Complex(1.0));
  CHECK(one.d1 == a);
  CHECK(one.d2 == a * a);
  const DividedDifference two = exp_divided_difference({a, b}, 0.0);
  CHECK(two.value == Complex(0.0));
  CHECK(two.d1 == Complex(1.0));
  CHECK(std::abs(two.d2 - (a + b)) < kDividedDifferenceTolerance);
  const DividedDifference three = exp_divided_difference({a, b, c}, 0.0);
  CHECK(three.value == Complex(0.0));
  CHECK(three.d1 == Complex(0.0));
  CHECK(three.d2 == Complex(1.0));
  CHECK_THROWS_AS((void)exp_divided_difference({}, 1.0), std::invalid_argument);
}

TEST_CASE("undamped single DOF step response and free vibration") {
  const double m = 2.0, k = 8.0, force = 3.0;
  const double w = std::sqrt(k / m);
  SUBCASE("step") {
    const ModalSolution sol(single_dof(m, 0.0, k, step(force)));
    CHECK(std::abs(sol.natural_frequencies()(0) - w) < kClosedFormTolerance);
    const double scale = force / k;
    for (double t : {0.0, 0.3, 1.0, 4.0, 25.0}) {
      CAPTURE(t);
      const LtiState s = sol.at(t);
      CHECK(relative_error(s.q(0), scale * (1.0 - std::cos(w * t)), scale) < kClosedFormTolerance);
      CHECK(relative_error(s.v(0), scale * w * std::sin(w * t), scale * w) < kClosedFormTolerance);
      CHECK(relative_error(s.a(0), force / m * std::cos(w * t), force / m) < kClosedFormTolerance);
    }
  }
  SUBCASE("free vibration") {
    const double x0 = 0.4, v0 = -1.3;
    TimeTerm none = polynomial({});
    const ModalSolution sol(single_dof(m, 0.0, k, none, x0, v0));
    const double scale = std::hypot(x0, v0 / w);
    for (double t : {0.0, 0.3, 1.0, 4.0, 25.0}) {
      CAPTURE(t);
      const LtiState s = sol.at(t);
      const double x = x0 * std::cos(w * t) + v0 / w * std::sin(w * t);
      const double v = -x0 * w * std::sin(w * t) + v0 * std::cos(w * t);
      CHECK(relative_error(s.q(0), x, scale) < kClosedFormTolerance);
      CHECK(relative_error(s.v(0), v, scale * w) < kClosedFormTolerance);
      CHECK(relative_error(s.a(0), -w * w * x, scale * w * w) < kClosedFormTolerance);
    }
  }
}

TEST_CASE("zero-frequency mode: rigid-body motion under step and polynomial loads") {
  const double m = 2.5;
  SUBCASE("step with initial conditions") {
    const double force = 1.5, x0 = 0.2, v0 = -0.7;
    const ModalSolution sol(single_dof(m, 0.0, 0.0, step(force), x0, v0));
    CHECK(sol.natural_frequencies()(0) == 0.0);
    for (double t : {0.0, 0.5, 3.0, 40.0}) {
      CAPTURE(t);
      const LtiState s = sol.at(t);
      const double x = x0 + v0 * t + force * t * t / (2.0 * m);
      CHECK(relative_error(s.q(0), x, std::max(1.0, std::abs(x))) < kClosedFormTolerance);
      CHECK(relative_error(s.v(0), v0 + force * t / m, std::max(1.0, force * t / m)) <
            kClosedFormTolerance);
      CHECK(relative_error(s.a(0), force / m, force / m) < kClosedFormTolerance);
    }
  }
  SUBCASE("linear ramp") {
    const ModalSolution sol(single_dof(m, 0.0, 0.0, polynomial({0.0, 1.0})));
    for (double t : {0.0, 0.5, 3.0, 40.0}) {
      CAPTURE(t);
      const LtiState s = sol.at(t);
      const double x = t * t * t / (6.0 * m);
      CHECK(relative_error(s.q(0), x, std::max(1.0, x)) < kClosedFormTolerance);
      CHECK(relative_error(s.v(0), t * t / (2.0 * m), std::max(1.0, t * t / (2.0 * m))) <
            kClosedFormTolerance);
      CHECK(relative_error(s.a(0), t / m, std::max(1.0, t / m)) < kClosedFormTolerance);
    }
  }
}

TEST_CASE("polynomial forcing of an oscillator satisfies the equation and rest initial state") {
  const LtiSystem sys = single_dof(1.5, 0.4, 6.0, polynomial({1.0, -2.0, 0.5, 0.25}));
  const ModalSolution sol(sys);
  const LtiState s0 = sol.at(0.0);
  CHECK(std::abs(s0.q(0)) < kClosedFormTolerance);
  CHECK(std::abs(s0.v(0)) < kClosedFormTolerance);
  for (double t : {0.0, 0.2, 1.0, 5.0, 20.0}) {
    CAPTURE(t);
    CHECK(equation_residual(sys, sol.at(t), t) < kResidualTolerance);
  }
}

TEST_CASE("resonance: x'' + w^2 x = sin(w t) grows linearly") {
  const double w = 1.7;
  const ModalSolution sol(single_dof(1.0, 0.0, w * w, harmonic(1.0, w)));
  for (double t : {0.0, 0.4, 2.0, 10.0, 30.0}) {
    CAPTURE(t);
    const LtiState s = sol.at(t);
    const double scale = std::max(1.0, t) / (2.0 * w);
    const double x = (std::sin(w * t) - w * t * std::cos(w * t)) / (2.0 * w * w);
    const double v = t * std::sin(w * t) / 2.0;
    const double a = (std::sin(w * t) + w * t * std::cos(w * t)) / 2.0;
    CHECK(relative_error(s.q(0), x, scale) < kClosedFormTolerance);
    CHECK(relative_error(s.v(0), v, scale * w) < kClosedFormTolerance);
    CHECK(relative_error(s.a(0), a, scale * w * w) < kClosedFormTolerance);
  }
}

TEST_CASE("damped single DOF step response against closed forms") {
  const double m = 1.0, w = 2.0, force = 3.0;
  const double k = m * w * w;
  const double scale = force / k;
  for (double zeta : {0.1, 1.0 - 1e-9, 1.0, 2.5}) {
    CAPTURE(zeta);
    const double c = 2.0 * zeta * w * m;
    const ModalSolution sol(single_dof(m, c, k, step(force)));
    for (double t : {0.0, 0.25, 1.0, 3.0, 12.0}) {
      CAPTURE(t);
      double x = 0.0, v = 0.0;
      if (zeta < 1.0) {
        const double wd = w * std::sqrt(1.0 - zeta * zeta);
        const double decay = std::exp(-zeta * w * t);
        x = scale * (1.0 - decay * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t)));
        v = scale * decay * w * w / wd * std::sin(wd * t);
      } else if (zeta == 1.0) {
        x = scale * (1.0 - std::exp(-w * t) * (1.0 + w * t));
        v = scale * w * w * t * std::exp(-w * t);
      } else {
        const double root = w * std::sqrt(zeta * zeta - 1.0);
        const double s1 = -zeta * w + root, s2 = -zeta * w - root;
        const double e1 = std::exp(s1 * t), e2 = std::exp(s2 * t);
        x = scale * (1.0 - (s2 * e1 - s1 * e2) / (s2 - s1));
        v = -scale * s1 * s2 * (e1 - e2) / (s2 - s1);
      }
      const LtiState s = sol.at(t);
      CHECK(relative_error(s.q(0), x, scale) < kClosedFormTolerance);
      CHECK(relative_error(s.v(0), v, scale * w) < kClosedFormTolerance);
      const double a = (force - c * v - k * x) / m;
      CHECK(relative_error(s.a(0), a, scale * w * w) < kClosedFormTolerance);
    }
  }
}

TEST_CASE("damped single DOF free vibration against the closed form") {
  const double w = 1.6, zeta = 0.15, x0 = 0.4, v0 = -1.1;
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  const ModalSolution sol(single_dof(1.0, 2.0 * zeta * w, w * w, polynomial({}), x0, v0));
  const double scale = std::hypot(x0, v0 / w);
  for (double t : {0.0, 0.4, 2.0, 9.0}) {
    CAPTURE(t);
    const double decay = std::exp(-zeta * w * t);
    const double b = (v0 + zeta * w * x0) / wd;
    const double x = decay * (x0 * std::cos(wd * t) + b * std::sin(wd * t));
    const double v = decay * ((b * wd - zeta * w * x0) * std::cos(wd * t) -
                              (x0 * wd + zeta * w * b) * std::sin(wd * t));
    const LtiState s = sol.at(t);
    CHECK(relative_error(s.q(0), x, scale) < kClosedFormTolerance);
    CHECK(relative_error(s.v(0), v, scale * w) < kClosedFormTolerance);
    CHECK(relative_error(s.a(0), -2.0 * zeta * w * v - w * w * x, scale * w * w) <
          kClosedFormTolerance);
  }
}

TEST_CASE("free-free two-mass chain: rounded zero eigenvalue is a rigid mode") {
  // With these numbers the solver returns the rigid-body eigenvalue as about -1e-17.
  LtiSystem sys;
  sys.M = Eigen::Vector2d(3.0, 7.0).asDiagonal();
  sys.K.resize(2, 2);
  sys.K << 0.7, -0.7, -0.7, 0.7;
  sys.forcing.push_back({Eigen::Vector2d(1.0, 0.0), step(2.0)});
  const ModalSolution sol(sys);
  CHECK(sol.natural_frequencies()(0) == 0.0);
  CHECK(std::abs(sol.natural_frequencies()(1) - std::sqrt(0.7 / 3.0 + 0.7 / 7.0)) <
        kClosedFormTolerance);
  // Momentum grows as F t; the centre of mass moves as F t^2 / (2 m_total).
  for (double t : {0.5, 3.0, 20.0}) {
    CAPTURE(t);
    const LtiState s = sol.at(t);
    CHECK(relative_error((sys.M * s.v).sum(), 2.0 * t, 2.0 * t) < kClosedFormTolerance);
    const double centre = (sys.M * s.q).sum() / 10.0;
    CHECK(relative_error(centre, t * t / 10.0, t * t / 10.0) < kClosedFormTolerance);
    CHECK(equation_residual(sys, s, t) < kResidualTolerance);
  }
}

TEST_CASE("exponential forcing against its closed form") {
  // x'' + w^2 x = A e^{rt}, rest start: x = A/(r^2 + w^2) (e^{rt} - cos wt - (r/w) sin wt).
  const double w = 1.3, amplitude = 0.8;
  for (double r : {-0.9, 0.0, 0.35}) {
    CAPTURE(r);
    const ModalSolution sol(single_dof(1.0, 0.0, w * w, exponential(amplitude, r)));
    const double g = amplitude / (r * r + w * w);
    for (double t : {0.0, 0.5, 2.0, 8.0}) {
      CAPTURE(t);
      const double x = g * (std::exp(r * t) - std::cos(w * t) - r / w * std::sin(w * t));
      const double v = g * (r * std::exp(r * t) + w * std::sin(w * t) - r * std::cos(w * t));
      const double scale = g * std::max(1.0, std::exp(r * t));
      const LtiState s = sol.at(t);
      CHECK(relative_error(s.q(0), x, scale) < kClosedFormTolerance);
      CHECK(relative_error(s.v(0), v, scale * w) < kClosedFormTolerance);
      CHECK(relative_error(s.a(0), amplitude * std::exp(r * t) - w * w * x, scale * w * w) <
            kClosedFormTolerance);
    }
  }
  SUBCASE("damped, forcing rate equal to a root") {
    // Roots -1 and -3; forcing e^{-t} resonates with the slow root: x = (t e^{-t})/2 - ...
    // Closed form: x = (1/2) t e^{-t} - (1/4) e^{-t} + (1/4) e^{-3t}.
    const LtiSystem sys = single_dof(1.0, 4.0, 3.0, exponential(1.0, -1.0));
    const ModalSolution sol(sys);
    for (double t : {0.0, 0.5, 2.0, 8.0}) {
      CAPTURE(t);
      const double x = 0.5 * t * std::exp(-t) - 0.25 * std::exp(-t) + 0.25 * std::exp(-3.0 * t);
      const LtiState s = sol.at(t);
      CHECK(std::abs(s.q(0) - x) < kClosedFormTolerance);
      CHECK(equation_residual(sys, s, t) < kResidualTolerance);
    }
  }
}

TEST_CASE("damped harmonic forcing settles to the steady-state amplitude and phase") {
  const double m = 1.0, c = 0.6, k = 4.0, amplitude = 2.0, w = 1.4, phase = 0.3;
  const ModalSolution sol(single_dof(m, c, k, harmonic(amplitude, w, phase), 0.5, -0.2));
  const Complex receptance = 1.0 / Complex(k - m * w * w, c * w);
  // Transient decays as e^{-c t / 2m}: e^{-60} by t = 200.
  for (double t : {200.0, 201.3}) {
    CAPTURE(t);
    const double x = amplitude * (receptance * std::polar(1.0, w * t + phase)).imag();
    const LtiState s = sol.at(t);
    CHECK(relative_error(s.q(0), x, amplitude * std::abs(receptance)) < kClosedFormTolerance);
  }
}

TEST_CASE("3-DOF system: frequencies, equation of motion, delayed step") {
  LtiSystem sys = three_dof();
  SUBCASE("natural frequencies") {
    const ModalSolution sol(sys);
    const Eigen::VectorXd& w = sol.natural_frequencies();
    REQUIRE(w.size() == 3);
    CHECK(std::abs(w(0) - 0.740310) < kQuotedFrequencyTolerance);
    CHECK(std::abs(w(1) - 1.825742) < kQuotedFrequencyTolerance);
    CHECK(std::abs(w(2) - 2.387874) < kQuotedFrequencyTolerance);
  }
  SUBCASE("equation residual and initial state") {
    sys.q0 = Eigen::Vector3d(0.1, -0.2, 0.05);
    sys.v0 = Eigen::Vector3d(0.0, 0.3, -0.1);
    sys.forcing.push_back({Eigen::Vector3d(1.0, 0.0, -1.0), harmonic(0.5, 0.9, 0.2)});
    const ModalSolution sol(sys);
    const LtiState s0 = sol.at(0.0);
    CHECK((s0.q - sys.q0).norm() < kResidualTolerance);
    CHECK((s0.v - sys.v0).norm() < kResidualTolerance);
    for (double t : {0.0, 0.3, 1.0, 5.0, 20.0, 100.0}) {
      CAPTURE(t);
      CHECK(equation_residual(sys, sol.at(t), t) < kResidualTolerance);
    }
  }
  SUBCASE("undamped step response oscillates about the static solution") {
    // From rest, q(t) = q_s - sum_i a_i cos(w_i t): the time mean over [0, T] is q_s up to
    // |sin(w_i T) / (w_i T)| <= 1 / (w_min T) of each modal amplitude (|a_i| <= |q_s| here).
    const ModalSolution sol(sys);
    const Eigen::Vector3d q_static = sys.K.ldlt().solve(Eigen::Vector3d(0.0, 2.0, 1.0));
    const int samples = 20000;
    const double dt = 0.05;  // midpoint rule, error O((w dt)^2) relative
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 0; i < samples; ++i) sum += sol.at(dt * (i + 0.5)).q;
    const double window = samples * dt;
    // Three modes, each off by at most 1 / (w_min T), plus the midpoint-rule error.
    const double mean_tolerance = 3.0 / (0.74 * window) + 1e-3;
    CHECK((sum / samples - q_static).lpNorm<Eigen::Infinity>() <
          mean_tolerance * q_static.lpNorm<Eigen::Infinity>());
  }
  SUBCASE("delayed step leaves the system at rest before it starts") {
    sys.forcing[0].term = step(1.0, 1.5);
    const ModalSolution sol(sys);
    for (double t : {0.0, 0.7, 1.4999999}) {
      CAPTURE(t);
      const LtiState s = sol.at(t);
      CHECK(s.q.norm() == 0.0);
      CHECK(s.v.norm() == 0.0);
      CHECK(s.a.norm() == 0.0);
    }
    // H(0) = 1: at the step the acceleration is the right limit M^{-1} F.
    const LtiState on = sol.at(1.5);
    CHECK(on.q.norm() == 0.0);
    const Eigen::Vector3d a_expected(0.0, 0.5, 0.25);
    CHECK((on.a - a_expected).norm() < kResidualTolerance);
    for (double t : {1.5, 2.0, 10.0}) {
      CAPTURE(t);
      CHECK(equation_residual(sys, sol.at(t), t) < kResidualTolerance);
    }
  }
  SUBCASE("step started before t = 0 acts from t = 0") {
    sys.forcing[0].term = step(1.0, -2.0);
    const ModalSolution early(sys);
    sys.forcing[0].term = step(1.0, 0.0);
    const ModalSolution at_zero(sys);
    for (double t : {0.0, 0.8, 3.0}) {
      CAPTURE(t);
      CHECK((early.at(t).q - at_zero.at(t).q).norm() == 0.0);
    }
  }
}

TEST_CASE("3-DOF system with Rayleigh damping") {
  LtiSystem sys = three_dof();
  sys.C = 0.1 * sys.M + 0.02 * sys.K;
  sys.q0 = Eigen::Vector3d(0.1, -0.2, 0.05);
  sys.v0 = Eigen::Vector3d(-0.3, 0.0, 0.2);
  const ModalSolution sol(sys);
  const LtiState s0 = sol.at(0.0);
  CHECK((s0.q - sys.q0).norm() < kResidualTolerance);
  CHECK((s0.v - sys.v0).norm() < kResidualTolerance);
  for (double t : {0.0, 0.3, 1.0, 5.0, 20.0, 100.0}) {
    CAPTURE(t);
    CHECK(equation_residual(sys, sol.at(t), t) < kResidualTolerance);
  }
  // Slowest decay rate zeta_i w_i = 0.05 + 0.01 w_i^2 >= 0.055: e^{-33} by t = 600.
  const Eigen::Vector3d q_static = sys.K.ldlt().solve(Eigen::Vector3d(0.0, 2.0, 1.0));
  const LtiState late = sol.at(600.0);
  CHECK((late.q - q_static).lpNorm<Eigen::Infinity>() <
        kStaticLimitTolerance * q_static.lpNorm<Eigen::Infinity>());
  CHECK(late.v.lpNorm<Eigen::Infinity>() < kStaticLimitTolerance);
}

TEST_CASE("non-classical damping is refused, classical dashpots are accepted") {
  LtiSystem sys = three_dof();
  SUBCASE("dashpot on a DOF shared by two modes") {
    sys.C = Eigen::Vector3d(0.0, 0.5, 0.0).asDiagonal();
    CHECK_THROWS_WITH_AS(ModalSolution{sys}, doctest::Contains("damping is not classical"),
                         ExactSolutionUnavailable);
  }
  SUBCASE("dashpot on the decoupled DOF is classical") {
    sys.C = Eigen::Vector3d(0.5, 0.0, 0.0).asDiagonal();
    const ModalSolution sol(sys);
    for (double t : {0.5, 4.0}) CHECK(equation_residual(sys, sol.at(t), t) < kResidualTolerance);
  }
  SUBCASE("repeated frequencies: any damping within the multiple eigenspace is classical") {
    // Two free unit masses with coupled dashpots: K = 0, every basis is modal.
    LtiSystem free;
    free.M = Eigen::Matrix2d::Identity();
    free.K = Eigen::Matrix2d::Zero();
    free.C.resize(2, 2);
    free.C << 2.0, -1.0, -1.0, 3.0;
    free.v0 = Eigen::Vector2d(1.0, 0.0);
    free.forcing.push_back({Eigen::Vector2d(0.0, 1.0), step(1.0)});
    const ModalSolution sol(free);
    const LtiState s0 = sol.at(0.0);
    CHECK((s0.v - free.v0).norm() < kResidualTolerance);
    CHECK(s0.q.norm() < kResidualTolerance);
    for (double t : {0.0, 0.5, 4.0}) {
      CAPTURE(t);
      CHECK(equation_residual(free, sol.at(t), t) < kResidualTolerance);
    }
  }
}

TEST_CASE("invalid systems are refused") {
  SUBCASE("singular mass matrix") {
    LtiSystem sys = three_dof();
    sys.M(2, 2) = 0.0;
    CHECK_THROWS_WITH_AS(ModalSolution{sys}, doctest::Contains("mass matrix is not positive"),
                         ExactSolutionUnavailable);
    sys.M = Eigen::Matrix3d::Ones();
    CHECK_THROWS_AS(ModalSolution{sys}, ExactSolutionUnavailable);
  }
  SUBCASE("indefinite stiffness") {
    LtiSystem sys = three_dof();
    sys.K(0, 0) = -10.0;
    CHECK_THROWS_WITH_AS(ModalSolution{sys}, doctest::Contains("not positive semi-definite"),
                         ExactSolutionUnavailable);
  }
  SUBCASE("asymmetric stiffness") {
    LtiSystem sys = three_dof();
    sys.K(1, 2) += 1e-6;
    CHECK_THROWS_WITH_AS(ModalSolution{sys}, doctest::Contains("not symmetric"),
                         ExactSolutionUnavailable);
  }
  SUBCASE("inconsistent sizes") {
    LtiSystem sys = three_dof();
    sys.forcing[0].b = Eigen::Vector2d(1.0, 1.0);
    CHECK_THROWS_AS(ModalSolution{sys}, std::invalid_argument);
    sys = three_dof();
    sys.C = Eigen::Matrix2d::Identity();
    CHECK_THROWS_AS(ModalSolution{sys}, std::invalid_argument);
  }
  SUBCASE("negative time") {
    const ModalSolution sol(three_dof());
    CHECK_THROWS_AS((void)sol.at(-1.0), std::invalid_argument);
  }
}
