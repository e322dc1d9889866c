// Every scheme converges to the exact solution as rtol shrinks, at the rate IDA's and CVODE's
// tolerance proportionality promises (global error ∝ rtol to first order), and penalty converges
// in its weight (error ∝ 1/w). These carry the subtlest logic of each scheme (index weights,
// error-test exclusions, projection), which an error that stalls or ignores rtol would expose.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/compare.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/references/embedded_scenes.hpp"
#include "validation/references/exact_solution.hpp"

using namespace condyn;

namespace test_scheme_convergence {

namespace {

struct Errors {
  double displacement = 0.0, reaction = 0.0;
};

Errors errors_of(const SceneSpec& spec, Scheme scheme) {
  const Model model = build_model(spec);
  const Trajectory run = test::solved(model, test::under(spec.solve, scheme)).trajectory;
  const auto err = relative_error(run, exact_trajectory(model, spec.solve.output_times()));
  return {err.displacement, err.reaction};
}

}  // namespace

TEST_CASE("every multiplier scheme and projection: error shrinks in proportion to rtol") {
  // Tolerance proportionality of a variable-order BDF is approximate; 0.7-1.3 rejects both a
  // stalled error (slope ~0) and an error that does not respond to rtol. Reactions come from
  // λ, an index-2 or index-3 unknown for some schemes, held to the same band.
  for (const char* scene : {"chapter_5_5_1", "chapter_5_6_2"}) {
    for (Scheme scheme : {Scheme::index1, Scheme::baumgarte, Scheme::ggl, Scheme::index2,
                          Scheme::index3, Scheme::projection}) {
      const std::string name = std::string(scene) + " " + to_string(scheme);
      CAPTURE(name);
      SceneSpec spec = parse_scene_text(embedded_scene(scene).text, scene);
      std::vector<double> log_rtol, log_u, log_r;
      for (double rtol : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
        spec.solve.rtol = rtol;
        spec.solve.atol = rtol * 1e-2;
        const Errors e = errors_of(spec, scheme);
        log_rtol.push_back(std::log10(rtol));
        log_u.push_back(std::log10(e.displacement));
        log_r.push_back(std::log10(e.reaction));
      }
      const double order_u = test::least_squares_slope(log_rtol, log_u),
                   order_r = test::least_squares_slope(log_rtol, log_r);
      MESSAGE(name << ": observed order in rtol " << order_u << " (u), " << order_r
                   << " (reactions)");
      CHECK(order_u >= 0.7);
      CHECK(order_u <= 1.3);
      // Every scheme's reactions come from λ at acceleration level at the rows
      // (dae/formulations/row_multipliers.hpp), so they converge with u. index3's own λ, an index-3
      // unknown out of the error test in which BDF loses order under variable steps (Brenan,
      // Campbell & Petzold, Numerical Solution of IVPs in DAEs, 1996, ch. 3), had given 0.57 on
      // §5.5.1 and 0.61 on §5.6.2; from acceleration level 0.82 on both.
      CHECK(order_r >= 0.7);
      CHECK(order_r <= 1.3);
    }
  }
}

TEST_CASE("penalty: error shrinks in proportion to 1/w") {
  // The penalty formulation solves a nearby unconstrained problem whose constraint violation is
  // O(1/w) (the chapter's penalty method); at a tight rtol the integration error is far below it
  // for the weights used here, so log error against log w has slope -1.
  SceneSpec spec = parse_scene_text(embedded_scene("chapter_5_5_1").text, "chapter_5_5_1");
  spec.solve.rtol = 1e-11;
  spec.solve.atol = 1e-13;
  std::vector<double> log_w, log_u;
  for (double w : {1e3, 1e4, 1e5, 1e6}) {
    spec.solve.penalty_weight = w;
    const Errors e = errors_of(spec, Scheme::penalty);
    MESSAGE("w " << w << ": error " << e.displacement);
    log_w.push_back(std::log10(w));
    log_u.push_back(std::log10(e.displacement));
  }
  const double order = test::least_squares_slope(log_w, log_u);
  MESSAGE("observed order in w: " << order);
  CHECK(order <= -0.9);
  CHECK(order >= -1.1);
}

}  // namespace test_scheme_convergence
