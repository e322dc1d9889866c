// The elimination path converges to the exact solution as rtol shrinks, at the rate IDA's
// tolerance proportionality promises (global error ∝ rtol to first order).
#include <doctest/doctest.h>

#include <cmath>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/compare.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/references/embedded_scenes.hpp"
#include "validation/references/exact_solution.hpp"

using namespace condyn;

namespace test_elimination_convergence {

TEST_CASE("elimination error shrinks in proportion to rtol") {
  for (const char* scene : {"chapter_5_5_1", "chapter_5_6_2"}) {
    CAPTURE(scene);
    SceneSpec spec = parse_scene_text(embedded_scene(scene).text, scene);
    std::vector<double> log_rtol, log_err;
    for (double rtol : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
      spec.solve.rtol = rtol;
      spec.solve.atol = rtol * 1e-2;
      const Model model = build_model(spec);
      const SolveResult result = test::solved(model, test::under(spec.solve, Scheme::elimination));
      const Trajectory& run = result.trajectory;
      const SolveSummary& summary = result.summary;
      const double err =
          relative_error(run, exact_trajectory(model, spec.solve.output_times())).displacement;
      MESSAGE("rtol " << rtol << ": error " << err << ", " << summary.steps << " steps");
      log_rtol.push_back(std::log10(rtol));
      log_err.push_back(std::log10(err));
    }
    const double slope = test::least_squares_slope(log_rtol, log_err);
    MESSAGE("observed order in rtol: " << slope);
    // Tolerance proportionality of a variable-order BDF is approximate; 0.7-1.3 rejects both a
    // stalled error (slope ~0) and an error that does not respond to rtol.
    CHECK(slope >= 0.7);
    CHECK(slope <= 1.3);
  }
}

}  // namespace test_elimination_convergence
