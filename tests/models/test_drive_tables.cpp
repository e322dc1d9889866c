// A drive given as a table (piecewise linear): its rate jumps at every sample, where the run stops
// and restarts (Model::breakpoints), the velocities jump onto the rows at the new rate, and the
// steps between samples see their segment's slope (TimeTable::slope's one-sided derivative).
// Checked against the exact kinematics: a crank whose angle is the table.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/time_table.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_drive_tables {

TEST_CASE("a table drive: the run stops at its kinks and follows its exact kinematics") {
  const test::Sandbox box;
  box.write("drive.csv", test::kCrankDriveTable);
  const test::BuiltScene built =
      test::built(parse_scene_file(box.write("scene.toml", test::kTableDrivenCrank).string()));
  const Model& model = built.model;
  const TimeTable table = parse_time_table(test::kCrankDriveTable, "angle");
  REQUIRE(model.breakpoints(1.2) == std::vector<double>{0.3, 0.55, 1.0});
  const int rx = model.dof_at("crank.ux"), ry = model.dof_at("crank.uy");
  // The angle and rate are the table's to the integration's accuracy: 100 (rtol + atol) on
  // O(1) angles and rates (observed below 1e-9 under every scheme). Before, index1 kept the
  // velocity through the kinks (the rate at 0.3 stayed 2 rad/s: an angle error of 0.4 at 0.4 s).
  constexpr double kTolerance = 100 * (1e-8 + 1e-10);
  for (const Scheme scheme : {Scheme::index1, Scheme::baumgarte, Scheme::ggl, Scheme::index2,
                              Scheme::index3, Scheme::projection}) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult r = test::solved(model, test::under(built.spec.solve, scheme));
    CHECK(r.summary.restarts >= 3);  // at 0.3, 0.55 and 1.0
    const Trajectory& run = r.trajectory;
    double worst_angle = 0.0, worst_rate = 0.0;
    for (std::size_t k = 0; k < run.t.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      const double ux = run.u(rx, col), uy = run.u(ry, col);
      const double angle = std::atan2(uy, ux);
      // The unit x axis turns at ω: u' = ω perp(u), so ω = u × u'.
      const double rate = ux * run.v(ry, col) - uy * run.v(rx, col);
      worst_angle = std::max(worst_angle, std::abs(angle - table.value(run.t[k])));
      worst_rate = std::max(worst_rate, std::abs(rate - table.slope(run.t[k])));
    }
    MESSAGE(std::string(to_string(scheme))
            << ": angle error " << worst_angle << ", rate error " << worst_rate << ", "
            << r.summary.restarts << " restarts");
    CHECK(worst_angle < kTolerance);
    CHECK(worst_rate < kTolerance);
  }
}

TEST_CASE("a table's slope as a segment sees it: one-sided at the sample that ends it") {
  const TimeTable table = parse_time_table(test::kCrankDriveTable, "angle");
  // A slope is a quotient of two differences of O(1) samples: a few ulps (4 eps) relative.
  constexpr double kRoundoff = 4 * std::numeric_limits<double>::epsilon();
  const auto near = [](double x) { return doctest::Approx(x).epsilon(kRoundoff); };
  // Plain evaluation: right-continuous (the segment that starts at the sample).
  CHECK(table.slope(0.3) == near(-2.0));
  // From a segment that began at 0.1 (before the kink): the left slope up to and at 0.3, and a
  // step that lands an ulp beyond it still counts as at it.
  CHECK(table.slope(0.3, 0.1) == near(2.0));
  CHECK(table.slope(std::nextafter(0.3, 1.0), 0.1) == near(2.0));
  CHECK(table.slope(0.4, 0.1) == near(-2.0));  // past the segment's end: slope(t)
  // A segment that began at the kink sees the right slope.
  CHECK(table.slope(0.4, 0.3) == near(-2.0));
  // Before the first sample and after the last: 0, and 0 from the side of the constant.
  CHECK(table.slope(1.0, 0.9) == near(2.0 / 3.0));
  CHECK(table.slope(1.1, 1.0) == 0.0);
}

}  // namespace test_drive_tables
