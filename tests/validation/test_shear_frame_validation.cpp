// The five-storey shear frame of issue 13's "Done when" (models/scenes/shear_frame_el_centro.toml:
// SI units, rigid floors as constraints, Rayleigh damping from two (frequency, ratio) pairs, the
// El Centro 1940 NS record as a tabulated ground acceleration) under every scheme that applies,
// against the exact modal solution for piecewise-linear excitation (validation/modal_exact.hpp).

#include <doctest/doctest.h>

#include <string>

#include "models/scene_parser.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/exact_solution.hpp"

using namespace condyn;

TEST_CASE("shear frame under El Centro: every scheme agrees with the exact solution") {
  auto scene = test::built(parse_scene_file(std::string(CONDYN_SOURCE_DIR) +
                                            "/models/scenes/shear_frame_el_centro.toml"));
  scene.spec.solve.rtol = 1e-10;
  scene.spec.solve.atol = 1e-12;
  scene.spec.solve.output_step = 0.1;  // 313 rows: the record's kinks fall between outputs too
  // Relative max-norm errors over all DOFs and outputs, observed 2026-11-25 with this scene at
  // rtol 1e-10 (`condyn compare ... --tolerances 1e-10`): u 1.3e-9 to 1.7e-9 for elimination,
  // index1, Baumgarte, GGL and index2, 3.5e-8 for projection, 4.2e-7 for index3 (its positions
  // are the index-3 DAE's: least accurate per tolerance, docs/schemes.md); reactions 1e-8 to
  // 1e-7 (6e-6 for index3). The issue asks 1e-7 on displacements at tight tolerance.
  struct Case {
    Scheme scheme;
    double u_bound, reaction_bound;
  };
  const Case cases[] = {{Scheme::elimination, 1e-7, 1e-6}, {Scheme::index1, 1e-7, 1e-6},
                        {Scheme::baumgarte, 1e-7, 1e-6},   {Scheme::ggl, 1e-7, 1e-6},
                        {Scheme::index2, 1e-7, 1e-6},      {Scheme::projection, 1e-7, 1e-6},
                        {Scheme::index3, 2e-6, 1e-4}};
  Trajectory exact;
  double peak_u = 0.0, peak_reaction = 0.0;
  for (const Case& c : cases) {
    const std::string name = to_string(c.scheme);
    CAPTURE(name);
    const SolveResult run = test::solved(scene.model, test::under(scene.spec.solve, c.scheme));
    if (exact.t.empty()) {
      exact = exact_trajectory(scene.model, run.trajectory.t);
      peak_u = exact.u.cwiseAbs().maxCoeff();
      peak_reaction = exact.reaction.cwiseAbs().maxCoeff();
      MESSAGE("peak relative displacement " << peak_u << " m, peak floor force " << peak_reaction
                                            << " N");
      // The frame moves (peak roof displacement of centimetres) and its floors carry force.
      CHECK(peak_u > 1e-3);
      CHECK(peak_reaction > 1e3);
    }
    const double err_u = (run.trajectory.u - exact.u).cwiseAbs().maxCoeff() / peak_u;
    const double err_r =
        (run.trajectory.reaction - exact.reaction).cwiseAbs().maxCoeff() / peak_reaction;
    MESSAGE(name << ": relative error u " << err_u << ", reactions " << err_r);
    CHECK(err_u < c.u_bound);
    CHECK(err_r < c.reaction_bound);
  }
}
