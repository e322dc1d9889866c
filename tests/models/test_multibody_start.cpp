// A mechanism's Model (models/assembly/multibody_model.cpp, multibody_start.cpp): its start
// checked against the joints within 1e-8 of the model's size, or projected keeping what
// [initial] keep names; its joints reported in the chapter's terms.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "models/systems/multibody_system.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_multibody_start {

using condyn::test::build_error;
using condyn::test::check_build_error;
using condyn::test::replace;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The projection stops when every row is met to 1e-10 of its terms' size (its convergence test,
// models/assembly/initial_projection.cpp); the bar's terms are of size 1.
constexpr double kProjected = 1e-10;

// A bar of length 1 hinged at the ground's O: its centre at (0.5, 0), turning at 2 rad/s, so
// its centre moves at (0, 1).
const std::string kBar = R"([model]
type = "multibody"
dimension = 2
gravity = [0.0, -9.81]
ground = { O = [0.0, 0.0] }

[[body]]
name = "bar"
mass = 1.0
inertia = 0.0833
position = [0.5, 0.0]
angle = 0.0
velocity = [0.0, 1.0]
angular_velocity = 2.0
points = { A = [-0.5, 0.0], B = [0.5, 0.0] }

[[joint]]
name = "hinge"
type = "revolute"
bodies = ["ground", "bar"]
points = ["O", "A"]

[solve]
t_end = 1.0
output_step = 0.1
)";

// A door hinged about the ground's z axis at P = (2, 0, 0).
const std::string kDoor = R"([model]
type = "multibody"
dimension = 3
ground = { P = [2.0, 0.0, 0.0], Q = [0.0, 0.0, 0.0] }
ground_axes = { z = [0.0, 0.0, 1.0] }

[[body]]
name = "door"
mass = 2.0
inertia = [1.0, 1.0, 1.5]
position = [2.0, 0.0, 0.0]
orientation = { quaternion = [1.0, 0.0, 0.0, 0.0] }
points = { hinge = [0.0, 0.0, 0.0] }
axes = { a = [0.0, 0.0, 1.0] }

[[joint]]
name = "pin"
type = "revolute"
bodies = ["ground", "door"]
points = ["P", "hinge"]
axes = ["z", "a"]

[solve]
t_end = 1.0
output_step = 0.1
)";

std::string scene_file(const std::string& name) {
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/multibody/" + name);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("a consistent mechanism builds: coordinates, rows, output map, joints reported") {
  BuildReport report;
  const Model model = build_model(parse_scene_text(kBar, "bar.toml"), report);
  CHECK(model.is_nonlinear());
  CHECK(model.dofs() == 4);  // rx, ry, ux, uy
  REQUIRE(model.outputs);
  CHECK(model.dof_names.front() == "bar.rx");
  REQUIRE(report.joints.size() == 1);
  CHECK(report.joints[0].find("hinge (revolute, ground - bar):") == 0);
  CHECK(report.joints[0].find("holonomic, scleronomic") != std::string::npos);
}

TEST_CASE("poses violating a joint beyond 1e-8 of the model's size are refused, naming it") {
  // The model's size is 1 (O to B): the bar's centre 1e-3 off is 1e5 times the tolerance.
  check_build_error(replace(kBar, "position = [0.5, 0.0]", "position = [0.501, 0.0]"),
                    "the initial poses violate joint 'hinge': row 'hinge.");
  // 1e-10 off, a hundredth of the tolerance: accepted as written.
  CHECK(build_error(replace(kBar, "position = [0.5, 0.0]", "position = [0.5000000001, 0.0]")) ==
        "");
  // The same 1e-3 in a model 1e6 times larger is 1e-9 of its size: accepted.
  const std::string large = replace(
      replace(replace(replace(kBar, "[-0.5, 0.0], B = [0.5, 0.0]", "[-5e5, 0.0], B = [5e5, 0.0]"),
                      "position = [0.5, 0.0]", "position = [500000.001, 0.0]"),
              "velocity = [0.0, 1.0]", "velocity = [0.0, 1e6]"),
      "inertia = 0.0833", "inertia = 8.33e10");
  CHECK(build_error(large) == "");
}

TEST_CASE("velocities violating a joint are refused, naming it") {
  // The centre of a bar turning at 2 rad/s about its end moves at 1, across the bar: 1.1 is not.
  check_build_error(replace(kBar, "velocity = [0.0, 1.0]", "velocity = [0.0, 1.1]"),
                    "the initial velocities violate joint 'hinge'");
  check_build_error(replace(kBar, "velocity = [0.0, 1.0]", "velocity = [0.1, 1.0]"),
                    "the initial velocities violate joint 'hinge'");
}

TEST_CASE("revolute axes that do not coincide at t = 0 are refused, naming the joint") {
  CHECK(build_error(kDoor) == "");
  check_build_error(replace(kDoor, "a = [0.0, 0.0, 1.0]", "a = [0.0, 0.01, 1.0]"),
                    "the initial poses violate joint 'pin'");
}

TEST_CASE("a drive not met by the start's velocity is refused") {
  check_build_error(
      replace(kBar, "points = [\"O\", \"A\"]",
              "points = [\"O\", \"A\"]\ndrive = { type = \"polynomial\", coefficients = "
              "[0.0, 3.0] }"),
      "the initial velocities violate joint 'hinge'");
  CHECK(
      build_error(replace(kBar, "points = [\"O\", \"A\"]",
                          "points = [\"O\", \"A\"]\ndrive = { type = \"polynomial\", coefficients "
                          "= [0.0, 2.0] }")) == "");
}

TEST_CASE("project = true keeps what keep names exactly and reports what moved") {
  // The bar written 0.1 rad off its hinge-consistent pose, its speed inconsistent too: keep the
  // angle and the angular velocity; the centre and its velocity move.
  const std::string text = replace(replace(kBar, "angle = 0.0", "angle = 0.1"), "[solve]",
                                   "[initial]\nproject = true\nkeep = [\"bar.angle\", "
                                   "\"bar.omega\"]\n[solve]");
  BuildReport report;
  const SceneSpec spec = parse_scene_text(text, "bar.toml");
  const Model model = build_model(spec, report);
  const Eigen::VectorXd q0 = build_multibody(*spec.model.mechanism).q0;
  const double ux = model.u0[model.dof_at("bar.ux")], uy = model.u0[model.dof_at("bar.uy")];
  // The angle kept: u is exactly the written pose's, never touched.
  CHECK(ux == q0[model.dof_at("bar.ux")]);
  CHECK(uy == q0[model.dof_at("bar.uy")]);
  CHECK(std::abs(std::atan2(uy, ux) - 0.1) <= 4 * kEps);
  // The angular velocity kept: ω = u × u' to the roundoff of the least-change solve, 64 eps
  // of the velocities' size (|u'| = 2).
  const double omega =
      ux * model.v0[model.dof_at("bar.uy")] - uy * model.v0[model.dof_at("bar.ux")];
  CHECK(std::abs(omega - 2.0) <= 64 * kEps * 2.0);
  // The centre moved to the hinge-consistent place, 0.5 along u from O.
  CHECK(std::abs(model.u0[model.dof_at("bar.rx")] - 0.5 * ux) <= kProjected);
  CHECK(std::abs(model.u0[model.dof_at("bar.ry")] - 0.5 * uy) <= kProjected);
  CHECK(report.initial_projection.find("keeping 2 values of [initial] keep exactly") !=
        std::string::npos);
  CHECK(report.initial_projection.find("bar.y: 0 -> ") != std::string::npos);
  CHECK(report.initial_projection.find("bar.angle:") == std::string::npos);
}

TEST_CASE("project = true with kept values no start meets is refused at initial.keep") {
  // The centre kept at (0.6, 0) with the angle kept at 0: the hinge needs it at (0.5, 0).
  check_build_error(
      replace(replace(kBar, "position = [0.5, 0.0]", "position = [0.6, 0.0]"), "[solve]",
              "[initial]\nproject = true\nkeep = [\"bar.angle\", \"bar.position\"]\n"
              "[solve]"),
      "initial.keep: with the values [initial] keep names held exactly, no start meets");
}

TEST_CASE("the example scenes build, the slider-crank's projection keeps the crank") {
  for (const char* name :
       {"slider_crank.toml", "four_bar.toml", "spatial_four_bar.toml", "pendulum_a01.toml"}) {
    CAPTURE(name);
    CHECK(build_error(scene_file(name)) == "");
  }
  BuildReport report;
  const SceneSpec spec = parse_scene_text(scene_file("slider_crank.toml"), "slider_crank.toml");
  const Model model = build_model(spec, report);
  const Eigen::VectorXd q0 = build_multibody(*spec.model.mechanism).q0;
  for (const char* kept : {"crank.ux", "crank.uy"}) {
    CAPTURE(kept);
    CHECK(model.u0[model.dof_at(kept)] == q0[model.dof_at(kept)]);
  }
  // With the crank vertical its pin moves horizontally at r ω = 0.1 · 2π, and so does the
  // slider: the rod translates (its ω stays 0, not reported), printed to 10 digits.
  CAPTURE(report.initial_projection);
  CHECK(report.initial_projection.find("slider.vx: 0 -> -0.6283185307") != std::string::npos);
  CHECK(report.initial_projection.find("rod.omega:") == std::string::npos);
}

}  // namespace test_multibody_start
