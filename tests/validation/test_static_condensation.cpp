// The exact modal reference with massless DOFs (validation/references/static_condensation.hpp): a
// singular M is condensed statically, and the result matches the closed form of the condensed
// system.
#include "validation/references/static_condensation.hpp"

#include <doctest/doctest.h>

#include <cmath>

#include "tests/modal_fixtures.hpp"

namespace test_static_condensation {

using namespace condyn::test::modal;

namespace {

/// Mass m on DOF 0, massless DOF 1; springs k1 from ground to 1 and k2 between 1 and 0 (in
/// series, 1/k = 1/k1 + 1/k2); harmonic load F sin(wt) on the massless DOF. Condensed by hand:
/// u1 = (F sin wt + k2 u0)/(k1 + k2), so m u0'' + k u0 = (k2/(k1 + k2)) F sin wt.
LtiSystem series_springs(double c0 = 0.0, double c1 = 0.0) {
  const double m = 2.0, k1 = 30.0, k2 = 20.0;
  LtiSystem s;
  s.M = Eigen::MatrixXd::Zero(2, 2);
  s.M(0, 0) = m;
  s.K.resize(2, 2);
  s.K << k2, -k2, -k2, k1 + k2;
  if (c0 != 0.0 || c1 != 0.0) {
    s.C = Eigen::MatrixXd::Zero(2, 2);
    s.C(0, 0) = c0;
    s.C(1, 1) = c1;
  }
  Eigen::VectorXd b = Eigen::VectorXd::Zero(2);
  b(1) = 1.0;
  s.forcing.push_back({b, harmonic(5.0, 3.0)});
  s.q0 = Eigen::VectorXd::Zero(2);
  s.q0(0) = 0.1;
  s.v0 = Eigen::VectorXd::Zero(2);
  return s;
}

}  // namespace

TEST_CASE("a massless DOF between two springs: the exact solution is the condensed one") {
  const double m = 2.0, k1 = 30.0, k2 = 20.0, F = 5.0, w = 3.0;
  const double k = k1 * k2 / (k1 + k2), share = k2 / (k1 + k2);
  const ModalSolution full(series_springs(0.4));
  // The condensed system by hand, damping on the massive DOF included.
  const ModalSolution hand(single_dof(m, 0.4, k, harmonic(share * F, w), 0.1, 0.0));
  REQUIRE(full.natural_frequencies().size() == 1);
  CHECK(std::abs(full.natural_frequencies()(0) - std::sqrt(k / m)) <= 1e-14 * std::sqrt(k / m));
  for (double t : {0.0, 0.2, 1.0, 3.7, 12.0}) {
    CAPTURE(t);
    const LtiState s = full.at(t), h = hand.at(t);
    CHECK(relative_error(s.q(0), h.q(0), 0.1) < 1e-13);
    CHECK(relative_error(s.v(0), h.v(0), 1.0) < 1e-13);
    CHECK(relative_error(s.a(0), h.a(0), 1.0) < 1e-13);
    // The massless DOF's row, k2 (u1 − u0) + k1 u1 = F sin wt, and its derivatives.
    const double f = F * std::sin(w * t), fd = F * w * std::cos(w * t), fdd = -w * w * f;
    CHECK(std::abs((k1 + k2) * s.q(1) - k2 * s.q(0) - f) < 1e-12);
    CHECK(std::abs((k1 + k2) * s.v(1) - k2 * s.v(0) - fd) < 1e-12);
    CHECK(std::abs((k1 + k2) * s.a(1) - k2 * s.a(0) - fdd) < 1e-11);
  }
}

TEST_CASE("static condensation refuses what is not static, saying why") {
  // Damping on the massless DOF makes its row first order.
  CHECK_THROWS_WITH_AS((void)ModalSolution{series_springs(0.0, 0.3)},
                       doctest::Contains("damping acts on the massless directions"),
                       ExactSolutionUnavailable);
  // A massless DOF nothing holds: K's row and column on it zero.
  LtiSystem loose = series_springs();
  loose.K << 20.0, 0.0, 0.0, 0.0;
  CHECK_THROWS_WITH_AS((void)ModalSolution{loose},
                       doctest::Contains("stiffness does not hold the massless directions"),
                       ExactSolutionUnavailable);
  // No mass at all.
  LtiSystem none = series_springs();
  none.M.setZero();
  CHECK_THROWS_WITH_AS((void)ModalSolution{none}, doctest::Contains("nothing has inertia"),
                       ExactSolutionUnavailable);
  // A regular M is left to the modal solution itself.
  LtiSystem regular = series_springs();
  regular.M(1, 1) = 1.0;
  CHECK_FALSE(condense_massless(regular).has_value());
}

}  // namespace test_static_condensation
