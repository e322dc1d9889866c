// The exact modal solver on single-DOF systems against closed forms.
#include "validation/references/modal_exact.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include "tests/modal_fixtures.hpp"

namespace test_modal_exact {

using namespace condyn::test::modal;

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

}  // namespace test_modal_exact
