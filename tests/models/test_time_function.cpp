#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "models/core/time_function.hpp"

namespace test_time_function {

using condyn::TimeFunction;
using condyn::TimeTerm;

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kH = 1e-4;
// Central differences with h = 1e-4 on the functions below (|f| ≤ 4, |f'''|, |f''''| ≤ 30 on the
// sampled t): the second difference's roundoff 4 eps |f| / h² ≈ 4e-7 dominates its truncation
// h² |f''''| / 12 ≈ 3e-8, and the first difference's errors, h² |f'''| / 6 ≈ 5e-8 and eps |f| / h,
// are below their sum (observed 1.1e-8 and 8e-9, relative to 1 + |f'| and 1 + |f''|).
constexpr double kFiniteDifferenceTolerance = 4 * kEps * 4.0 / (kH * kH) + kH * kH * 30.0 / 12.0;

TimeTerm harmonic(double a, double w, double p) {
  TimeTerm t;
  t.kind = TimeTerm::Kind::harmonic;
  t.amplitude = a;
  t.omega = w;
  t.phase = p;
  return t;
}
TimeTerm exponential(double a, double r) {
  TimeTerm t;
  t.kind = TimeTerm::Kind::exponential;
  t.amplitude = a;
  t.rate = r;
  return t;
}
TimeTerm polynomial(std::vector<double> c) {
  TimeTerm t;
  t.coefficients = std::move(c);
  return t;
}
TimeTerm step(double a, double s) {
  TimeTerm t;
  t.kind = TimeTerm::Kind::step;
  t.amplitude = a;
  t.start = s;
  return t;
}
}  // namespace

TEST_CASE("time functions: derivatives agree with central differences") {
  const TimeFunction f(
      {harmonic(1.5, 2.0, 0.3), exponential(0.7, -0.4), polynomial({1, -2, 0.5, 0.25})});
  for (double t : {0.0, 0.7, 2.5}) {
    const double d1 = (f.value(t + kH) - f.value(t - kH)) / (2 * kH);
    const double d2 = (f.value(t + kH) - 2 * f.value(t) + f.value(t - kH)) / (kH * kH);
    CHECK(f.derivative(1, t) == doctest::Approx(d1).epsilon(kFiniteDifferenceTolerance));
    CHECK(f.derivative(2, t) == doctest::Approx(d2).epsilon(kFiniteDifferenceTolerance));
  }
}

TEST_CASE("time functions: closed forms") {
  CHECK(TimeFunction({polynomial({0, 1, 0.5})}).value(2.0) ==
        doctest::Approx(4.0).epsilon(8 * kEps));
  CHECK(TimeFunction({harmonic(2, 3, 0)}).derivative(2, 0.4) ==
        doctest::Approx(-18 * std::sin(1.2)).epsilon(8 * kEps));
  CHECK(TimeFunction({exponential(2, 0.5)}).derivative(1, 1.0) ==
        doctest::Approx(std::exp(0.5)).epsilon(8 * kEps));
}

TEST_CASE("time functions: steps switch on at start, H(0) = 1, and by segment") {
  const TimeFunction f({step(2.0, 1.0)});
  CHECK(f.value(0.999) == 0.0);
  CHECK(f.value(1.0) == 2.0);
  CHECK(f.derivative(0, 1.0, 0.5) == 0.0);  // segment that started before the step: still off
  CHECK(f.derivative(1, 1.5) == 0.0);
  REQUIRE(f.breakpoints().size() == 1);
  CHECK(f.breakpoints()[0] == 1.0);
  CHECK(TimeFunction({step(2.0, 0.0)}).breakpoints().empty());
  CHECK(!f.is_constant());
  CHECK(TimeFunction({step(2.0, 0.0)}).is_constant());
}

TEST_CASE("time functions: antiderivative is zero at 0 and differentiates back") {
  const TimeFunction f(
      {harmonic(1.5, 2.0, 0.3), exponential(0.7, -0.4), polynomial({1, -2, 3}), step(0.5, 0.0)});
  const TimeFunction F = f.antiderivative();
  // The constants cancel to roundoff of the terms' size (|a/ω|, |a/r| ≤ 1.75: 4 eps × 2); the
  // derivative of each term is its closed form again, a few ulps (both observed exact).
  CHECK(std::abs(F.value(0.0)) < 4 * kEps * 2.0);
  for (double t : {0.3, 1.1, 4.0}) {
    CHECK(F.derivative(1, t) == doctest::Approx(f.value(t)).epsilon(16 * kEps));
  }
  // Eq. 5.14: u'x1 = 1 + t integrates to t + t²/2.
  const TimeFunction g = TimeFunction({polynomial({1, 1})}).antiderivative();
  CHECK(g.value(2.0) == doctest::Approx(4.0).epsilon(8 * kEps));
  CHECK_THROWS_AS((void)TimeFunction({step(1.0, 2.0)}).antiderivative(), std::invalid_argument);
}

TEST_CASE("time functions: antiderivatives of slow harmonics and exponentials keep their digits") {
  // ∫₀ᵗ A sin(ωs + φ) ds and ∫₀ᵗ A exp(rs) ds for ωt, rt ≪ 1 against their Taylor series (three
  // terms: the next is below 1e-30 relative here). As A/ω (cos φ − cos(ωt + φ)) written with two
  // terms, ω = 1e-12 kept 4 digits (6e-5 absolute at t = 0 after a velocity row's constant).
  const double t = 2.0;
  struct Case {
    double w, phase;
  };
  for (const Case c : {Case{1e-6, 0.3}, Case{1e-12, 0.3}, Case{1e-14, 0.3}, Case{-1e-12, 0.3},
                       Case{1e-300, 0.3}, Case{-1e-300, 0.3}, Case{5e-324, 0.3}, Case{1e-10, 0.0},
                       Case{-1e-300, 0.0}, Case{1e-8, std::numbers::pi}}) {
    const double w = c.w, phase = c.phase;  // plain variables: clang 14 cannot capture bindings
    CAPTURE(w);
    CAPTURE(phase);
    const TimeFunction F = TimeFunction({harmonic(1.5, w, phase)}).antiderivative();
    // Phase 0 (π): the value is the small ω t²/2 term alone (with sin π's roundoff), which a phase
    // shifted by π/2 and rounded, then evaluated near a zero of the sine, lost.
    const double series =
        1.5 * (std::sin(phase) * (t - w * w * t * t * t / 6) + std::cos(phase) * w * t * t / 2);
    CHECK(F.value(0.0) == 0.0);
    CHECK(F.value(t) == doctest::Approx(series).epsilon(8 * kEps));
    CHECK(F.derivative(1, t) == doctest::Approx(1.5 * std::sin(w * t + phase)).epsilon(8 * kEps));
    const TimeFunction E = TimeFunction({exponential(0.7, w)}).antiderivative();
    CHECK(E.value(0.0) == 0.0);
    CHECK(E.value(t) ==
          doctest::Approx(0.7 * (t + w * t * t / 2 + w * w * t * t * t / 6)).epsilon(8 * kEps));
    // Not integrated again: ∫ (f − f(0)) = ∫ f − f(0) t would cancel as before.
    CHECK_THROWS_AS((void)F.antiderivative(), std::invalid_argument);
    CHECK_THROWS_AS((void)E.antiderivative(), std::invalid_argument);
  }
  // A cosine drive (phase π/2) integrates to sin ωt / ω exactly: no constant is left at t = 0.
  const TimeFunction C =
      TimeFunction({harmonic(1.0, 1e-12, std::numbers::pi / 2)}).antiderivative();
  CHECK(C.value(0.0) == 0.0);
  CHECK(C.value(t) == doctest::Approx(t).epsilon(8 * kEps));
  CHECK(C.describe() == "1*int_0^t sin(1e-12*s+1.5708) ds");
}

TEST_CASE("time functions: a harmonic's phase is never added to omega t") {
  // 1e4 sin(1e-4 t + π): ωt + π moves in steps of ulp(π) = 4.4e-16, so the drive was a staircase
  // of 4e-12 (GGL then failed to start on such a drive of amplitude 1e6). By the angle sum the
  // value is a few ulps of its size; the reference sums in long double (64-bit mantissa: the sum's
  // rounding is 2e-19 of π).
  const TimeFunction f({harmonic(1e4, 1e-4, std::numbers::pi)});
  for (double t : {0.3, 1.0, 7.77}) {
    CAPTURE(t);
    const long double arg = static_cast<long double>(1e-4 * t) + std::numbers::pi;
    const auto exact = static_cast<double>(1e4L * std::sin(arg));
    const auto slope = static_cast<double>(1e4L * 1e-4L * std::cos(arg));
    CHECK(std::abs(f.value(t) - exact) <= 16 * kEps * std::abs(exact));  // observed 3.5 ulps
    CHECK(std::abs(f.derivative(1, t) - slope) <= 16 * kEps * std::abs(slope));
  }
}

TEST_CASE("time functions: zero and constant detection") {
  CHECK(TimeFunction().is_zero());
  CHECK(TimeFunction::constant(0.0).is_zero());
  CHECK(!TimeFunction::constant(1.0).is_zero());
  CHECK(TimeFunction::constant(1.0).is_constant());
  CHECK(!TimeFunction({polynomial({0, 1})}).is_constant());
  CHECK(!TimeFunction({harmonic(1, 2, 0)}).is_constant());
}

TEST_CASE("time functions: describe signs, refuse derivative orders above 2") {
  CHECK(TimeFunction({step(2.0, -1.0)}).describe() == "2*H(t+1)");
  CHECK(TimeFunction({harmonic(1.0, 2.0, -0.5)}).describe() == "1*sin(2*t-0.5)");
  CHECK_THROWS_AS((void)TimeFunction({harmonic(1.0, 2.0, 0.0)}).derivative(3, 0.0),
                  std::invalid_argument);
}

}  // namespace test_time_function
