// When compare may print a drift-growth law (validation/studies/drift_growth.hpp): only for a
// steady power law over at least a decade of time above roundoff, in a run of many oscillations;
// otherwise the reason. Synthetic drift logs with known laws.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "dae/run/trajectory.hpp"
#include "validation/studies/drift_growth.hpp"

using namespace condyn;

namespace test_drift_growth_assessment {

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();

/// A drift log of `n` steps over (0, t_end], drift = f(t), over `oscillations` oscillations of
/// the motion (two velocity reversals each, spread evenly).
template <class F>
std::vector<StepRecord> log_of(double t_end, int n, F f, double oscillations = 1000.0) {
  std::vector<StepRecord> steps;
  for (int k = 1; k <= n; ++k) {
    const double t = t_end * k / n;
    steps.push_back({t, f(t), 0.0, static_cast<long>(2.0 * oscillations * k / n)});
  }
  return steps;
}

constexpr double kFloor = 1e-14;

}  // namespace

TEST_CASE("a steady t^2 law over two decades is fitted with its exponent") {
  const auto steps = log_of(1000.0, 20000, [](double t) { return 1e-12 * t * t; });
  const DriftGrowthAssessment a = assess_drift_growth(steps, kFloor);
  REQUIRE_MESSAGE(a.fit.has_value(), a.reason);
  // An exact power law: the least-squares slope is 2 up to roundoff in the logs, accumulated over
  // at most 20000 points in the sums: 20000 eps (observed 8e-14 relative).
  CHECK(a.fit->exponent == doctest::Approx(2.0).epsilon(20000 * kEps));
  CHECK(a.reason.empty());
}

TEST_CASE("a bounded drift that settles early is fitted as p near 0") {
  const auto steps =
      log_of(1000.0, 20000, [](double t) { return 1e-8 * (1.0 - std::exp(-t / 0.5)); });
  const DriftGrowthAssessment a = assess_drift_growth(steps, kFloor);
  REQUIRE_MESSAGE(a.fit.has_value(), a.reason);
  CHECK(std::abs(a.fit->exponent) < 0.05);  // saturated from t_end/100 on: flat
}

TEST_CASE("a transient that rises steeply then saturates is not a growth law") {
  // The inclined roller's GGL drift: from roundoff up to its Newton-tolerance bound within the
  // run. Before the fix compare printed "p = 2.24, theory: bounded" for such a log.
  const auto saturating =
      log_of(8.0, 800, [](double t) { return 1e-7 * std::min(1.0, std::pow(t / 2.0, 12.0)); });
  const DriftGrowthAssessment a = assess_drift_growth(saturating, kFloor);
  CHECK_FALSE(a.fit.has_value());
  CHECK(a.reason.find("no steady power law") != std::string::npos);
  CHECK(a.quarter_exponents.size() == 4);
}

TEST_CASE("drift at roundoff, too short a window, too few oscillations: reasons, no fit") {
  SUBCASE("roundoff") {
    const auto steps = log_of(100.0, 1000, [](double) { return 1e-17; });
    const DriftGrowthAssessment a = assess_drift_growth(steps, kFloor);
    CHECK_FALSE(a.fit.has_value());
    CHECK(a.reason.find("stays at roundoff") != std::string::npos);
  }
  SUBCASE("above roundoff over less than a decade") {
    // Rises through the floor at t = 50 of 100: 0.3 decades.
    const auto steps = log_of(100.0, 1000, [](double t) { return 1e-14 * t * t / 2500.0; });
    const DriftGrowthAssessment a = assess_drift_growth(steps, kFloor);
    CHECK_FALSE(a.fit.has_value());
    CHECK(a.reason.find("at least a decade") != std::string::npos);
  }
  SUBCASE("one swing of a mechanism (Andrews over 0.03 s: 4 oscillations)") {
    const auto steps = log_of(
        0.03, 1000, [](double t) { return 1e-6 * t * t; }, 4.0);
    const DriftGrowthAssessment a = assess_drift_growth(steps, kFloor);
    CHECK_FALSE(a.fit.has_value());
    CHECK(a.reason.find("4 oscillations") != std::string::npos);
  }
}

TEST_CASE("velocity reversals are counted per DOF, the fastest-reversing one reported") {
  VelocityReversals reversals;
  const std::vector<std::pair<double, double>> v = {{1, 1},   {-1, 0}, {1, 2},  {-1, 3}, {1, 0},
                                                    {-1, -1}, {1, -2}, {-1, 0}, {1, 5}};
  long last = 0;
  for (const auto& [a, b] : v) last = reversals(Eigen::Vector2d(a, b));
  CHECK(last == 8);  // DOF 1: 8 sign changes; DOF 2 (zeros keep the last sign): 2
}

TEST_CASE("a velocity chattering about zero is not counted as oscillating") {
  // index3's velocities are out of the error test and may flip sign at roundoff near rest: on
  // Andrews' mechanism that doubled the count of oscillations and let a 0.03 s run be fitted.
  VelocityReversals reversals;
  long last = 0;
  last = reversals(Eigen::VectorXd::Constant(1, 1.0));
  for (int k = 0; k < 100; ++k)
    last = reversals(Eigen::VectorXd::Constant(1, k % 2 ? 1e-6 : -1e-6));
  CHECK(last == 0);
  last = reversals(Eigen::VectorXd::Constant(1, -0.5));  // a real reversal
  CHECK(last == 1);
}

}  // namespace test_drift_growth_assessment
