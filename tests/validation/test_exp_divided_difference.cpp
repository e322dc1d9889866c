// The divided differences of exp behind the modal solver: explicit formulas, confluent limits,
// time derivatives.
#include "validation/references/modal_exact.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include "tests/modal_fixtures.hpp"

namespace test_exp_divided_difference {

using namespace condyn::test::modal;

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

}  // namespace test_exp_divided_difference
