// RATTLE over 10^4 periods of IFToMM A01 (validation/iftomm/A01_long_run.toml, at a coarser step):
// the energy error stays bounded (no drift) while the position constraints stay at Newton's
// tolerance, where the BDF schemes' errors grow (docs/schemes.md "RATTLE").

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_rattle_validation {

TEST_CASE("rattle on A01 over 10^4 periods: bounded energy error, constraints held") {
  // h = 0.05 (h sqrt(g/L) = 0.16), 473,560 steps. Over the first and the last 1000 periods the
  // largest energy errors agree within a factor 1.5 (a drift would grow them with time); the
  // error is O(h²): below 0.05 m g L. The position row holds to Newton's tolerance
  // (rtol |u| + atol = 1.01e-6 at rtol 1e-6, atol 1e-8; its quadratic convergence leaves far
  // less). Observed: see the message.
  SceneSpec spec = parse_scene_file(CONDYN_SOURCE_DIR "/validation/iftomm/A01_long_run.toml");
  spec.solve.scheme = Scheme::rattle;
  spec.solve.step = 0.05;
  const auto built = test::built(std::move(spec));
  const SolveResult r = test::solved(built.model, built.spec.solve);
  const Eigen::VectorXd& e = r.trajectory.energy;
  const double mgl = 9.81;
  const Eigen::Index tenth = e.size() / 10;
  const double first = (e.head(tenth).array() - e[0]).abs().maxCoeff() / mgl;
  const double last = (e.tail(tenth).array() - e[0]).abs().maxCoeff() / mgl;
  MESSAGE("energy error / mgL: " << first << " (first 1000 periods), " << last
                                 << " (last 1000); drift " << r.summary.max_drift_position
                                 << " (positions), " << r.summary.max_drift_velocity
                                 << " (velocities); " << r.summary.steps << " steps");
  constexpr double kNoDrift = 1.5, kEnergyBound = 0.05;
  CHECK(last <= kNoDrift * first);
  CHECK(first <= kEnergyBound);
  constexpr double kNewtonTolerance = 1.01e-6;
  CHECK(r.summary.max_drift_position <= kNewtonTolerance);
}

}  // namespace test_rattle_validation
