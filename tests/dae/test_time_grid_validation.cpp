// Load steps at random multiples k·dt of output steps written as a user writes them, and steps one
// ulp off an output, under every scheme against the closed form (tests/load_step_runs.hpp); the
// time grid itself and the other load-step runs are in test_time_grid.cpp.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "tests/load_step_runs.hpp"

using namespace condyn;

namespace test_time_grid_validation {

using namespace condyn::test::load_steps;

TEST_CASE("random k·dt load steps, and steps one ulp off an output, run under every scheme") {
  std::mt19937 rng(2026);  // fixed seed: the same cases every run
  for (const auto& [m, p] : std::vector<std::pair<int, int>>{{1, 1}, {7, 2}, {25, 3}}) {
    // dt = m·10^-p written as a user would ("7e-2"); load steps at k·dt written the same way.
    const std::string dt_literal = std::to_string(m) + "e-" + std::to_string(p);
    const double dt = std::stod(dt_literal);
    CAPTURE(dt_literal);
    std::uniform_int_distribution<int> pick(1, 19);
    std::vector<std::string> literals;
    std::vector<double> starts;
    for (int i = 0; i < 4; ++i) {
      literals.push_back(std::to_string(pick(rng) * m) + "e-" + std::to_string(p));
      starts.push_back(std::stod(literals.back()));
    }
    std::sort(starts.begin(), starts.end());
    check_every_scheme(scene(literals, dt_literal, literal(20 * dt)), starts, dt, 20 * dt);
  }
  const double below = std::nextafter(0.5, 0.0), above = std::nextafter(0.2, 1.0);
  check_every_scheme(scene({literal(below), literal(above)}, "0.1", "1.0"), {above, below}, 0.1,
                     1.0);
}

}  // namespace test_time_grid_validation
