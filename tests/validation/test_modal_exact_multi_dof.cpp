// The exact modal solver on multi-DOF systems: frequencies, the equation of motion, damping
// (classical accepted, non-classical refused), invalid systems.
#include "validation/references/modal_exact.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include "models/core/eigen_decompositions.hpp"
#include "tests/modal_fixtures.hpp"

namespace test_modal_exact_multi_dof {

using namespace condyn::test::modal;

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
  SUBCASE("singular mass matrix that stiffness does not hold, or an indefinite one") {
    // (A singular M whose null space stiffness holds is condensed statically:
    // tests/validation/test_static_condensation.cpp.)
    LtiSystem sys = three_dof();
    sys.M(2, 2) = 0.0;
    sys.K.row(2).setZero();
    sys.K.col(2).setZero();
    if (sys.C.size() != 0) {
      sys.C.row(2).setZero();
      sys.C.col(2).setZero();
    }
    CHECK_THROWS_WITH_AS(ModalSolution{sys},
                         doctest::Contains("stiffness does not hold the massless directions"),
                         ExactSolutionUnavailable);
    sys = three_dof();
    sys.M = -Eigen::Matrix3d::Identity();
    CHECK_THROWS_WITH_AS(ModalSolution{sys}, doctest::Contains("mass matrix is not positive"),
                         ExactSolutionUnavailable);
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

}  // namespace test_modal_exact_multi_dof
