// Issue 13's validation, the truss version of the shear building: a three-storey braced frame
// written as a truss2d scene (SI units: columns, floor beams and one brace per storey as bars,
// floor masses at the nodes, the base supported), each floor's two horizontal DOFs tied by a
// rigid-floor constraint, Rayleigh damping from two (frequency, ratio) pairs and the El Centro
// 1940 NS record as ground motion along x, under every scheme that applies, against the exact
// modal solution for piecewise-linear excitation (validation/references/modal_exact.hpp).

#include <doctest/doctest.h>

#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/exact_cases.hpp"
#include "tests/fixed_step_order.hpp"

using namespace condyn;

namespace test_truss_frame_validation {

namespace {

/// Storeys 3.5 m high, bays 6 m wide; columns EA 2e9 N, beams EA 1e9 N, braces EA 5e8 N (node
/// 2k+1 at the left, 2k+2 at the right of level k); 1e5 kg per floor node.
std::string frame_scene() {
  return std::string(R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [6.0, 0.0], [0.0, 3.5], [6.0, 3.5], [0.0, 7.0], [6.0, 7.0], [0.0, 10.5], [6.0, 10.5]]
masses = [0.0, 0.0, 1e5, 1e5, 1e5, 1e5, 1e5, 1e5]
supports = [1, 2]
members = [{ nodes = [1, 3], EA = 2e9 }, { nodes = [2, 4], EA = 2e9 }, { nodes = [3, 5], EA = 2e9 },
           { nodes = [4, 6], EA = 2e9 }, { nodes = [5, 7], EA = 2e9 }, { nodes = [6, 8], EA = 2e9 },
           { nodes = [3, 4], EA = 1e9 }, { nodes = [5, 6], EA = 1e9 }, { nodes = [7, 8], EA = 1e9 },
           { nodes = [1, 4], EA = 5e8 }, { nodes = [3, 6], EA = 5e8 }, { nodes = [5, 8], EA = 5e8 }]
damping = { rayleigh = { frequencies = [2.0, 10.0], ratios = [0.05, 0.05] } }
[ground_motion]
direction = "x"
acceleration = { type = "table", file = ")") +
         CONDYN_SOURCE_DIR + R"(/models/scenes/data/el_centro_1940_ns.csv", scale = 9.81 }
[[constraint]]
name = "floor1"
terms = { ux3 = 1.0, ux4 = -1.0 }
[[constraint]]
name = "floor2"
terms = { ux5 = 1.0, ux6 = -1.0 }
[[constraint]]
name = "floor3"
terms = { ux7 = 1.0, ux8 = -1.0 }
[solve]
t_end = 12.0
output_step = 0.1
rtol = 1e-10
atol = 1e-12
)";
}

}  // namespace

TEST_CASE("truss frame under El Centro: every scheme agrees with the exact solution") {
  const auto scene = test::built(parse_scene_text(frame_scene(), "truss_frame.toml"));
  // Bounds: the issue's 1e-7 on displacements at tight tolerance. Observed (peak
  // sway 0.103 m, peak reaction 2.9e6 N): u 1.4e-9 to 2.1e-9 (elimination, index1, Baumgarte,
  // GGL, index2), 2.9e-8 projection, 1.3e-6 index3 (its positions are the index-3 DAE's),
  // 5.1e-5 penalty (its weight's error); reactions 1.5e-9 to 3.1e-8, 1.4e-6, 5.7e-5.
  const test::ExactPeaks peak = test::check_against_exact(scene.model, scene.spec.solve,
                                                          {{Scheme::elimination, 1e-7, 1e-6},
                                                           {Scheme::index1, 1e-7, 1e-6},
                                                           {Scheme::baumgarte, 1e-7, 1e-6},
                                                           {Scheme::ggl, 1e-7, 1e-6},
                                                           {Scheme::index2, 1e-7, 1e-6},
                                                           {Scheme::projection, 1e-7, 1e-6},
                                                           {Scheme::penalty, 1e-3, 1e-1},
                                                           {Scheme::index3, 2e-6, 1e-4}});
  CHECK(peak.u > 1e-3);        // the frame sways by millimetres to centimetres (m)
  CHECK(peak.reaction > 1e4);  // the supports and floors carry force (N)
}

TEST_CASE("truss frame under El Centro: the Newmark family converges at order 2 to the exact one") {
  // Fixed steps h = 0.002 and h/2 (tests/fixed_step_order.hpp): the braced frame's highest
  // frequency is 137 rad/s (`condyn info`; h ω = 0.27 at h = 0.002).
  const auto scene = test::built(parse_scene_text(frame_scene(), "truss_frame.toml"));
  test::check_order_two("truss frame", scene.model, scene.spec.solve,
                        exact_trajectory(scene.model, scene.spec.solve.output_times()), 0.002);
}

}  // namespace test_truss_frame_validation
