// Load steps at ordinary times: output times, load steps and t_end merged with a tolerance relative
// to the time scale, so that the integrator is never asked for a time within its roundoff of where
// it stands (3 × 0.1 lies one ulp above 0.3: a step at 0.3 with output_step 0.1 used to stop with
// IDA_ILL_INPUT "tout too close to t0"). Every scheme, and the rows at exactly the expected times.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dae/integrators/step_driver.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/load_step_runs.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_time_grid {

using namespace condyn::test::load_steps;

TEST_CASE("time grid: an output one ulp from a load step is the load step") {
  const std::vector<double> outputs = {0.0, 0.1, 0.2, 3 * 0.1, 0.4, 0.5, 6 * 0.1, 7 * 0.1, 1.0};
  REQUIRE(3 * 0.1 != 0.3);  // the premise: k·h and the decimal differ
  const TimeGrid grid = make_time_grid(outputs, {0.3, 0.6, 0.7});
  CHECK(grid.stops == std::vector<double>{0.3, 0.6, 0.7});
  CHECK(grid.outputs == std::vector<double>{0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 1.0});
  CHECK_FALSE(grid.initial_stop);
  // One ulp before and after an output time.
  const double below = std::nextafter(0.5, 0.0), above = std::nextafter(0.5, 1.0);
  CHECK(make_time_grid(outputs, {below}).outputs[5] == below);
  CHECK(make_time_grid(outputs, {above}).outputs[5] == above);
  // Load steps within roundoff of each other are one stop (the last: all of them on after it);
  // within roundoff of t0 a restart before the first step; within roundoff of t_end, nothing.
  const TimeGrid close = make_time_grid(outputs, {0.3, std::nextafter(0.3, 1.0)});
  CHECK(close.stops == std::vector<double>{std::nextafter(0.3, 1.0)});
  const TimeGrid start = make_time_grid(outputs, {1e-300, 0.5});
  REQUIRE(start.initial_stop);
  CHECK(*start.initial_stop == 1e-300);
  CHECK(start.stops == std::vector<double>{0.5});
  CHECK(make_time_grid(outputs, {std::nextafter(1.0, 0.0)}).stops.empty());
  CHECK(make_time_grid(outputs, {std::nextafter(1.0, 0.0)}).outputs.back() == 1.0);
}

TEST_CASE("time grid: random k·dt load steps leave every kept time apart by more than roundoff") {
  std::mt19937 rng(12345);  // fixed seed: the same cases every run
  for (double dt : {0.1, 0.01, 0.001, 0.07, 1.0 / 3.0, 0.025}) {
    CAPTURE(dt);
    const double t_end = 1000 * dt;
    std::vector<double> outputs;
    for (int k = 0; k < 1000; ++k) outputs.push_back(k * dt);
    outputs.push_back(t_end);
    std::uniform_int_distribution<int> pick(1, 999);
    std::vector<double> breakpoints;
    for (int i = 0; i < 50; ++i) {
      // The decimal a user would write for k·dt, which may differ from k * dt by an ulp or two.
      breakpoints.push_back(std::stod(literal(pick(rng) * dt)));
    }
    std::sort(breakpoints.begin(), breakpoints.end());
    const TimeGrid grid = make_time_grid(outputs, breakpoints);
    CHECK(grid.outputs.size() == outputs.size());  // none lost, none added
    CHECK(grid.outputs.front() == 0.0);
    CHECK(grid.outputs.back() == t_end);
    for (std::size_t k = 1; k < grid.outputs.size(); ++k) {
      CHECK(grid.outputs[k] - grid.outputs[k - 1] > grid.tolerance);
    }
    for (std::size_t k = 1; k < grid.stops.size(); ++k) {
      CHECK(grid.stops[k] - grid.stops[k - 1] > grid.tolerance);
    }
    // Every output within roundoff of a stop is that stop.
    for (double t : grid.outputs) {
      for (double s : grid.stops) {
        if (std::abs(t - s) <= grid.tolerance) CHECK(t == s);
      }
    }
  }
}

TEST_CASE("load steps at 0.3, 0.6 and 0.7 with output_step 0.1 run under every scheme") {
  check_every_scheme(scene({"0.3", "0.6", "0.7"}, "0.1", "1.0"), {0.3, 0.6, 0.7}, 0.1, 1.0);
}

TEST_CASE("fifty load steps 1 ms apart run under every scheme") {
  std::vector<std::string> literals;
  std::vector<double> starts;
  for (int k = 1; k <= 50; ++k) {
    literals.push_back(std::to_string(k) + "e-3");  // 1e-3, 2e-3, ...: as a user writes them
    starts.push_back(std::stod(literals.back()));
  }
  check_every_scheme(scene(literals, "1e-3", "0.1"), starts, 1e-3, 0.1);
}

TEST_CASE("output times: a multiple of output_step is t_end only within the time axis' roundoff") {
  SolveSpec s;
  const auto times = [&s](double t_end, double h) {
    s.t_end = t_end;
    s.output_step = h;
    const std::vector<double> t = s.output_times();
    CHECK(static_cast<long>(t.size()) == s.output_count());
    return t;
  };
  // 1e-10 before t_end is a row of its own (it was dropped within 1e-9 output steps of t_end, and
  // a check at that time read the row of t_end).
  CHECK(times(1.0, 0.9999999999) == std::vector<double>{0.0, 0.9999999999, 1.0});
  CHECK(times(0.3000000001, 0.1) == std::vector<double>{0.0, 0.1, 0.2, 3 * 0.1, 0.3000000001});
  CHECK(times(1000.0, 999.9999999) == std::vector<double>{0.0, 999.9999999, 1000.0});
  // Within roundoff (3 × 0.1 is one ulp above 0.3): t_end alone.
  CHECK(times(0.3, 0.1) == std::vector<double>{0.0, 0.1, 0.2, 0.3});
  CHECK(times(1.0, 0.1).size() == 11);
  CHECK(times(1.0, 1.0) == std::vector<double>{0.0, 1.0});
  CHECK(times(1.0, 0.3) == std::vector<double>{0.0, 0.3, 0.6, 0.8999999999999999, 1.0});
  // The count agrees with the times over pairs drawn at random (the quotient's rounding).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-3.0, 3.0), steps(1.0, 2000.0);
  for (int i = 0; i < 2000; ++i) {
    const double t_end = std::pow(10.0, exponent(rng));
    (void)times(t_end, t_end / steps(rng));
    (void)times(t_end, t_end / std::round(steps(rng)));  // dividing it, to roundoff
  }
}

}  // namespace test_time_grid
