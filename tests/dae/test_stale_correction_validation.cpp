// GGL with IDA's stale Newton matrix on a tied lattice (dae/integrators/stale_correction.hpp): the
// algebraic rows see the unscaled correction, so linear constraints stay at roundoff over a run.
// The correction's own algebra is checked in test_stale_correction.cpp.
#include <doctest/doctest.h>

#include <string>

#include "dae/run/solve.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_stale_correction_validation {

TEST_CASE("GGL with a stale Newton matrix keeps a linear model's constraints to roundoff") {
  // A 40 x 5 truss lattice (EA 1e4, unit masses) under a step load of −1 on every free node's uy,
  // tied top to bottom in columns 10, 20 and 30, as the benchmark lattice (bench/lattice.py):
  // GGL's φ and ψ rows are linear, so every Newton correction, stale matrix or not, satisfies
  // them. With IDA's scaling of the whole correction by 2/(1 + cj/cj₀), this run drifted by
  // 2.1e-9 (largest displacement 0.54), now 1.7e-16.
  std::string extra;
  for (int i = 10; i < 40; i += 10) {
    extra += "[[constraint]]\nname = \"tie" + std::to_string(i) + "\"\nterms = { uy" +
             std::to_string(4 * 40 + i + 1) + " = 1.0, uy" + std::to_string(i + 1) + " = -1.0 }\n";
  }
  for (int j = 0; j < 5; ++j) {
    for (int i = 1; i < 40; ++i) {
      extra += "[[load]]\ndof = \"uy" + std::to_string(j * 40 + i + 1) +
               "\"\nvalue = { type = \"step\", amplitude = -1.0 }\n";
    }
  }
  std::string text = test::lattice(40, 5, extra, "scheme = \"ggl\"\nrtol = 1e-6\natol = 1e-8\n");
  for (auto at = text.find("EA = 1.0"); at != std::string::npos; at = text.find("EA = 1.0", at)) {
    text.replace(at, 8, "EA = 1e4");
  }
  const auto scene = test::built(parse_scene_text(text, "tied.toml"));
  const SolveResult r = test::solved(scene.model, scene.spec.solve);
  const double scale = r.trajectory.u.cwiseAbs().maxCoeff();
  REQUIRE(scale > 0.1);
  // Constraint rows of unit coefficients on displacements of size `scale`: a few ulps.
  CHECK(r.summary.max_drift_position <= 1e-14 * scale);
  CHECK(r.summary.max_drift_velocity <= 1e-14 * scale);
}

}  // namespace test_stale_correction_validation
