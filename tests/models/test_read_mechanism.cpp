// The scene reader's multibody part (docs/scenes.md, "Mechanisms of rigid bodies"): every key
// read into the Mechanism, and every bad input refused with FILE:LINE: key.path: problem.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "models/core/mechanism_keep.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_read_mechanism {

using condyn::test::check_parse_error;
using condyn::test::parse_error;
using condyn::test::replace;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A planar slider-crank: crank (length 1) hinged at O, rod (length 2) from its tip to a slider
// on the ground's x axis. Each case below changes one thing.
const std::string kPlanar = R"(name = "slider-crank"
[model]
type = "multibody"
dimension = 2
gravity = [0.0, -9.81]
ground = { O = [0.0, 0.0], S = [3.0, 0.0] }
ground_axes = { ex = [1.0, 0.0] }

[[body]]
name = "crank"
mass = 1.0
inertia = 0.0833
position = [0.5, 0.0]
angle = 0.0
velocity = [0.0, 0.5]
angular_velocity = 1.0
points = { A = [-0.5, 0.0], B = [0.5, 0.0] }

[[body]]
name = "rod"
mass = 2.0
inertia = 0.6667
position = [2.0, 0.0]
points = { B = [-1.0, 0.0], C = [1.0, 0.0] }

[[body]]
name = "slider"
mass = 0.5
inertia = 0.01
position = [3.0, 0.0]
points = { C = [0.0, 0.0] }
axes = { u = [2.0, 0.0] }

[[joint]]
name = "hinge_O"
type = "revolute"
bodies = ["ground", "crank"]
points = ["O", "A"]
drive = { type = "polynomial", coefficients = [0.0, 6.0] }

[[joint]]
name = "hinge_B"
type = "revolute"
bodies = ["crank", "rod"]
points = ["B", "B"]

[[joint]]
name = "hinge_C"
type = "revolute"
bodies = ["rod", "slider"]
points = ["C", "C"]

[[joint]]
name = "guide"
type = "prismatic"
bodies = ["ground", "slider"]
points = ["S", "C"]
axes = ["ex", "u"]

[[force]]
type = "spring_damper"
bodies = ["slider", "ground"]
points = ["C", "S"]
k = 100.0
c = 2.0
rest_length = 0.5

[[force]]
type = "rotational_spring_damper"
joint = "hinge_B"
k = 3.0
rest_angle = 0.1

[[force]]
type = "point_force"
body = "rod"
point = "C"
force = [1.0, { type = "harmonic", omega = 2.0 }]

[[force]]
type = "torque"
body = "crank"
torque = { type = "step", amplitude = 2.0 }

[solve]
t_end = 1.0
output_step = 0.1
)";

// A spatial pendulum: one body on a spherical joint, one on a revolute joint about z.
const std::string kSpatial = R"(name = "spatial"
[model]
type = "multibody"
dimension = 3
gravity = [0.0, 0.0, -9.81]
ground = { O = [0.0, 0.0, 0.0], P = [2.0, 0.0, 0.0] }
ground_axes = { z = [0.0, 0.0, 1.0] }

[[body]]
name = "bob"
mass = 1.0
inertia = [0.1, 0.2, 0.25]
position = [0.0, 0.0, -1.0]
orientation = { axis = [0.0, 0.0, 2.0], angle = 0.5 }
velocity = [0.1, 0.0, 0.0]
angular_velocity = [0.0, 0.1, 0.0]
points = { top = [0.0, 0.0, 1.0] }

[[body]]
name = "door"
mass = 2.0
inertia = [[1.0, 0.1, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 1.5]]
position = [2.0, 0.0, 0.0]
orientation = { quaternion = [1.0, 0.0, 0.0, 0.0] }
points = { hinge = [0.0, 0.0, 0.0] }
axes = { a = [0.0, 0.0, 1.0] }

[[joint]]
name = "ball"
type = "spherical"
bodies = ["ground", "bob"]
points = ["O", "top"]

[[joint]]
name = "pin"
type = "revolute"
bodies = ["ground", "door"]
points = ["P", "hinge"]
axes = ["z", "a"]

[[force]]
type = "torque"
body = "door"
torque = [0.0, 0.0, 1.0]

[solve]
t_end = 1.0
output_step = 0.1
)";

}  // namespace

TEST_CASE("a planar mechanism's every key is read") {
  const SceneSpec spec = parse_scene_text(kPlanar, "planar.toml");
  REQUIRE(spec.model.type == ModelSpec::Type::multibody);
  REQUIRE(spec.model.mechanism);
  const Mechanism& m = *spec.model.mechanism;
  CHECK(m.dimension == 2);
  CHECK(m.gravity == Mechanism::Vec3{0.0, -9.81, 0.0});
  REQUIRE(m.ground_points.size() == 2);
  CHECK(m.ground_points[1].name == "S");
  CHECK(m.ground_points[1].at == Mechanism::Vec3{3.0, 0.0, 0.0});
  REQUIRE(m.bodies.size() == 3);
  const auto& crank = m.bodies[0];
  CHECK(crank.name == "crank");
  CHECK(crank.mass == 1.0);
  CHECK(crank.inertia(2, 2) == 0.0833);
  CHECK(crank.position == Mechanism::Vec3{0.5, 0.0, 0.0});
  CHECK(crank.velocity == Mechanism::Vec3{0.0, 0.5, 0.0});
  CHECK(crank.angular_velocity == Mechanism::Vec3{0.0, 0.0, 1.0});
  CHECK(crank.points.size() == 2);
  CHECK(crank.where.line == 9);
  // An axis is a direction: [2, 0] is read as the unit vector [1, 0].
  CHECK(m.bodies[2].axes[0].at == Mechanism::Vec3{1.0, 0.0, 0.0});
  REQUIRE(m.joints.size() == 4);
  CHECK(m.joints[0].type == Mechanism::JointType::revolute);
  CHECK(m.joints[0].bodies == std::array<int, 2>{Mechanism::kGround, 0});
  CHECK(m.joints[0].points == std::array<int, 2>{0, 0});
  REQUIRE(m.joints[0].drive);
  CHECK(m.joints[0].drive->derivative(1, 0.0) == 6.0);
  CHECK(m.joints[1].bodies == std::array<int, 2>{0, 1});
  CHECK(m.joints[1].points == std::array<int, 2>{1, 0});
  CHECK(m.joints[3].type == Mechanism::JointType::prismatic);
  CHECK(m.joints[3].axes == std::array<int, 2>{0, 0});
  CHECK(m.joints[3].points == std::array<int, 2>{1, 0});
  REQUIRE(m.forces.size() == 4);
  CHECK(m.forces[0].type == Mechanism::ForceType::spring_damper);
  CHECK(m.forces[0].bodies == std::array<int, 2>{2, Mechanism::kGround});
  CHECK(m.forces[0].k == 100.0);
  CHECK(m.forces[0].c == 2.0);
  CHECK(m.forces[0].rest_length == 0.5);
  CHECK(m.forces[1].type == Mechanism::ForceType::rotational_spring_damper);
  CHECK(m.forces[1].joint == 1);
  CHECK(m.forces[1].rest_angle == 0.1);
  CHECK(m.forces[1].c == 0.0);
  CHECK(m.forces[2].type == Mechanism::ForceType::point_force);
  CHECK(m.forces[2].points[0] == 1);
  REQUIRE(m.forces[2].components.size() == 2);
  CHECK(m.forces[2].components[1].derivative(1, 0.0) == 2.0);  // d/dt sin(2t) at 0
  CHECK(m.forces[3].type == Mechanism::ForceType::torque);
  REQUIRE(m.forces[3].components.size() == 1);
  CHECK(m.forces[3].components[0].value(0.0) == 2.0);
}

TEST_CASE("a spatial mechanism's orientation, inertia and vectors are read") {
  const SceneSpec spec = parse_scene_text(kSpatial, "spatial.toml");
  const Mechanism& m = *spec.model.mechanism;
  CHECK(m.dimension == 3);
  const auto& bob = m.bodies[0];
  CHECK(bob.inertia.diagonal() == Eigen::Vector3d(0.1, 0.2, 0.25));
  // { axis, angle }: the axis normalized; the rotation about z by 0.5 rad.
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  CHECK(bob.orientation.coeffs().isApprox(expected.coeffs(), 4 * kEps));
  CHECK(bob.angular_velocity == Mechanism::Vec3{0.0, 0.1, 0.0});
  CHECK(m.bodies[1].inertia(0, 1) == 0.1);
  CHECK(m.bodies[1].inertia(1, 0) == 0.1);
  CHECK(m.joints[1].axes == std::array<int, 2>{0, 0});
  REQUIRE(m.forces[0].components.size() == 3);
  CHECK(m.forces[0].components[2].value(0.0) == 1.0);
}

TEST_CASE("[initial] keep and [output] points are read and checked against the bodies") {
  const SceneSpec spec =
      parse_scene_text(kPlanar +
                           "[initial]\nproject = true\nkeep = [\"crank.angle\", \"crank.omega\", "
                           "\"rod.position\"]\n[output]\npoints = [\"crank.B\", \"rod.C\"]\n",
                       "planar.toml");
  CHECK(spec.initial.keep ==
        std::vector<std::string>{"crank.angle", "crank.omega", "rod.position"});
  CHECK(spec.output.points == std::vector<std::string>{"crank.B", "rod.C"});
  std::string problem;
  const auto kept = kept_values(*spec.model.mechanism, "rod.position", problem);
  REQUIRE(kept.size() == 2);  // x and y in 2D
  CHECK(kept[1].kind == KeptValue::Kind::position);
  CHECK(kept[1].component == 1);
  const auto omega = kept_values(*spec.model.mechanism, "crank.angular_velocity", problem);
  REQUIRE(omega.size() == 1);  // about z alone in 2D
  CHECK(omega[0].component == 2);
}

TEST_CASE("names: unknown bodies, points and axes, with the nearest names, duplicates") {
  check_parse_error(
      replace(kPlanar, R"(bodies = ["crank", "rod"])", R"(bodies = ["crank", "rood"])"),
      "joint[2].bodies[2]: unknown body 'rood' (did you mean rod?");
  check_parse_error(replace(kPlanar, R"(points = ["B", "B"])", R"(points = ["B", "Bx"])"),
                    "joint[2].points[2]: unknown point 'Bx' of body 'rod' (did you mean B?");
  check_parse_error(replace(kPlanar, R"(axes = ["ex", "u"])", R"(axes = ["ey", "u"])"),
                    "joint[4].axes[1]: unknown axis 'ey' of the ground (did you mean ex?");
  check_parse_error(replace(kPlanar, R"(points = ["C", "S"])", R"(points = ["C", "T"])"),
                    "force[1].points[2]: unknown point 'T' of the ground");
  check_parse_error(replace(kPlanar, R"(joint = "hinge_B")", R"(joint = "hinge_b")"),
                    "force[2].joint: unknown joint 'hinge_b' (did you mean hinge_B");
  check_parse_error(replace(kPlanar, R"(body = "rod")", R"(body = "ground")"),
                    "force[3].body: the ground does not move");
  check_parse_error(replace(kPlanar, R"(name = "rod")", R"(name = "crank")"),
                    "body[2].name: body 'crank' is already body[1]");
  check_parse_error(replace(kPlanar, R"(name = "hinge_B")", R"(name = "hinge_O")"),
                    "joint[2].name: joint 'hinge_O' is already joint[1]");
  check_parse_error(replace(kPlanar, R"(name = "hinge_B")", R"(name = "rod")"),
                    "joint[2].name: 'rod' is also a body's name");
  check_parse_error(replace(kPlanar, R"(name = "rod")", R"(name = "ground")"),
                    "body[2].name: 'ground' is the fixed body's name");
  check_parse_error(replace(kPlanar, R"(name = "rod")", R"(name = "r.od")"), "holds a '.'");
  check_parse_error(replace(kPlanar, R"(bodies = ["crank", "rod"])", R"(bodies = ["rod", "rod"])"),
                    "joint[2].bodies: a joint connects two different bodies");
  check_parse_error(replace(kPlanar, "type = \"revolute\"\nbodies = [\"crank\"",
                            "type = \"revolut\"\nbodies = [\"crank\""),
                    "joint[2].type: unknown joint type 'revolut' (did you mean revolute?");
}

TEST_CASE("inertia: positive definite, the triangle inequality, symmetric") {
  check_parse_error(replace(kPlanar, "inertia = 0.0833", "inertia = 0.0"),
                    "body[1].inertia: must be > 0");
  check_parse_error(replace(kSpatial, "inertia = [0.1, 0.2, 0.25]", "inertia = [0.1, 0.2, 0.0]"),
                    "body[1].inertia: is not positive definite");
  check_parse_error(
      replace(kSpatial, "inertia = [0.1, 0.2, 0.25]", "inertia = [0.1, 0.2, 0.35]"),
      "body[1].inertia: violates the triangle inequality: principal moment 0.35 exceeds "
      "the sum of the other two, 0.3");
  // A lamina: Izz = Ixx + Iyy exactly, accepted.
  CHECK(parse_error(replace(kSpatial, "inertia = [0.1, 0.2, 0.25]", "inertia = [0.1, 0.2, 0.3]")) ==
        "");
  // A full tensor whose eigenvalues break the inequality: products of inertia matter.
  check_parse_error(replace(kSpatial, "[[1.0, 0.1, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 1.5]]",
                            "[[1.0, 0.9, 0.0], [0.9, 1.0, 0.0], [0.0, 0.0, 1.5]]"),
                    "body[2].inertia: violates the triangle inequality");
  check_parse_error(replace(kSpatial, "[[1.0, 0.1, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 1.5]]",
                            "[[1.0, 0.1, 0.0], [0.2, 1.0, 0.0], [0.0, 0.0, 1.5]]"),
                    "body[2].inertia: is not symmetric: entry (1, 2) = 0.1 but (2, 1) = 0.2");
  check_parse_error(replace(kSpatial, "inertia = [0.1, 0.2, 0.25]", "inertia = 0.1"),
                    "body[1].inertia: a spatial body's inertia is [Ixx, Iyy, Izz]");
  check_parse_error(replace(kPlanar, "inertia = 0.0833", "inertia = [0.1, 0.1, 0.1]"),
                    "body[1].inertia: a planar body's inertia is one number");
}

TEST_CASE("orientation: unit quaternions, nonzero axes, the dimension's keys") {
  check_parse_error(replace(kSpatial, "quaternion = [1.0, 0.0, 0.0, 0.0]",
                            "quaternion = [0.7071, 0.7071, 0.0, 0.0]"),
                    "body[2].orientation.quaternion: is not a unit quaternion (norm 0.99999");
  // Written to 17 digits, a unit quaternion passes.
  CHECK(parse_error(replace(kSpatial, "quaternion = [1.0, 0.0, 0.0, 0.0]",
                            "quaternion = [0.70710678118654757, 0.70710678118654757, 0.0, 0.0]")) ==
        "");
  check_parse_error(replace(kSpatial, "axis = [0.0, 0.0, 2.0]", "axis = [0.0, 0.0, 0.0]"),
                    "body[1].orientation.axis: needs a nonzero direction");
  check_parse_error(replace(kSpatial, "orientation = { axis", "angle = 0.5\norientation = { axis"),
                    "body[1].angle: a spatial body's orientation is orientation");
  check_parse_error(
      replace(kPlanar, "angle = 0.0", "orientation = { axis = [0.0, 0.0, 1.0], angle = 0.0 }"),
      "body[1].orientation: a planar body's orientation is its angle");
  check_parse_error(replace(kSpatial, "quaternion = [1.0, 0.0, 0.0, 0.0]",
                            "quaternion = [1.0, 0.0, 0.0, 0.0], angle = 1.0"),
                    "give either quaternion or { axis, angle }");
}

TEST_CASE("vectors: the dimension's length, axes nonzero") {
  check_parse_error(
      replace(kPlanar, "position = [0.5, 0.0]", "position = [0.5, 0.0, 0.0]"),
      "body[1].position: has 3 components; a vector of a 2D mechanism (dimension = 2) "
      "has 2");
  check_parse_error(replace(kSpatial, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, -9.81]"),
                    "model.gravity: has 2 components");
  check_parse_error(replace(kPlanar, "B = [0.5, 0.0] }", "B = [0.5] }"),
                    "body[1].points.B: has 1 components");
  check_parse_error(replace(kPlanar, "u = [2.0, 0.0]", "u = [0.0, 0.0]"),
                    "body[3].axes.u: an axis needs a nonzero direction");
  check_parse_error(replace(kPlanar, "ex = [1.0, 0.0]", "ex = [0.0, 0.0]"),
                    "model.ground_axes.ex: an axis needs a nonzero direction");
  check_parse_error(
      replace(kPlanar, "angular_velocity = 1.0", "angular_velocity = [0.0, 0.0, 1.0]"),
      "body[1].angular_velocity: a planar body's angular velocity is one number");
  check_parse_error(replace(kSpatial, "dimension = 3", "dimension = 4"),
                    "model.dimension: must be 2 (planar) or 3 (spatial)");
}

TEST_CASE("joints: spatial types in 2D, missing or extra axes, lengths") {
  check_parse_error(replace(kPlanar, "type = \"revolute\"\nbodies = [\"crank\"",
                            "type = \"spherical\"\nbodies = [\"crank\""),
                    "joint[2].type: a spherical joint is spatial: it needs [model] dimension = 3");
  check_parse_error(replace(kPlanar, "axes = [\"ex\", \"u\"]\n", ""),
                    "joint[4]: a planar prismatic joint needs axes");
  check_parse_error(replace(kSpatial, "axes = [\"z\", \"a\"]\n", ""),
                    "joint[2]: a spatial revolute joint needs axes");
  check_parse_error(
      replace(kPlanar, "points = [\"B\", \"B\"]", "points = [\"B\", \"B\"]\naxes = [\"B\", \"B\"]"),
      "joint[2].axes: a planar revolute joint takes no axes (it turns about z)");
  check_parse_error(replace(kSpatial, "points = [\"O\", \"top\"]",
                            "points = [\"O\", \"top\"]\naxes = [\"z\", \"z\"]"),
                    "joint[1].axes: a spatial spherical joint takes no axes");
  check_parse_error(replace(kPlanar, "points = [\"B\", \"B\"]", "points = [\"B\"]"),
                    "joint[2].points: a joint names two points");
  check_parse_error(
      replace(kPlanar, "points = [\"B\", \"B\"]", "points = [\"B\", \"B\"]\nlength = 1.0"),
      "joint[2].length: only a distance joint has a length");
  // A distance joint between points that coincide at t = 0 and no length: a length of 0.
  check_parse_error(replace(kPlanar, "type = \"revolute\"\nbodies = [\"crank\"",
                            "type = \"distance\"\nbodies = [\"crank\""),
                    "joint[2]: the distance joint's points coincide at t = 0");
  CHECK(parse_error(replace(kPlanar, "type = \"revolute\"\nbodies = [\"rod\"",
                            "type = \"distance\"\nlength = 0.5\nbodies = [\"rod\"")) == "");
}

TEST_CASE("drives: only on a coordinate, starting at 0, no jumps, tables accepted") {
  CHECK(parse_error(replace(
            kPlanar, "points = [\"S\", \"C\"]",
            "points = [\"S\", \"C\"]\ndrive = { type = \"harmonic\", omega = 1.0 }")) == "");
  check_parse_error(replace(kPlanar, "type = \"revolute\"\nbodies = [\"rod\"",
                            "type = \"distance\"\nlength = 0.1\ndrive = 0.0\nbodies = [\"rod\""),
                    "joint[3].drive: a distance joint has no coordinate to drive");
  check_parse_error(
      replace(kPlanar, "coefficients = [0.0, 6.0]", "coefficients = [0.1, 6.0]"),
      "joint[1].drive: is 0.1 at t = 0, but a drive counts the joint's coordinate from "
      "its value at t = 0");
  check_parse_error(replace(kPlanar, "drive = { type = \"polynomial\", coefficients = [0.0, 6.0] }",
                            "drive = { type = \"step\", start = 0.5 }"),
                    "joint[1].drive: a step at t = 0.5 would make the driven coordinate jump");
  // A harmonic with phase π is sin(π) = 1.2e-16 at t = 0: zero to roundoff, accepted.
  CHECK(parse_error(replace(kPlanar, "drive = { type = \"polynomial\", coefficients = [0.0, 6.0] }",
                            "drive = { type = \"harmonic\", omega = 2.0, phase = 3.141592653589793 "
                            "}")) == "");
}

TEST_CASE("forces: kinds, coefficients, the joint of a rotational spring, components") {
  check_parse_error(
      replace(kPlanar, "joint = \"hinge_B\"", "joint = \"guide\""),
      "force[2].joint: joint 'guide' is prismatic: a rotational spring-damper acts at a "
      "revolute joint");
  check_parse_error(replace(kPlanar, "k = 100.0", "k = -1.0"), "force[1].k: must be >= 0");
  check_parse_error(replace(kPlanar, "force = [1.0, { type", "force = [{ type"),
                    "force[3].force: needs 2 components");
  check_parse_error(replace(kSpatial, "torque = [0.0, 0.0, 1.0]", "torque = [0.0, 1.0]"),
                    "force[1].torque: needs 3 components");
  check_parse_error(replace(kPlanar, "type = \"spring_damper\"", "type = \"spring\""),
                    "force[1].type: unknown force type 'spring'");
  check_parse_error(replace(kPlanar, "rest_length = 0.5", "rest_lenght = 0.5"),
                    "force[1].rest_lenght: unknown key (did you mean rest_length?");
}

TEST_CASE("sections and keys a mechanism has no use for, and its keys elsewhere") {
  check_parse_error(kPlanar + "[[load]]\ndof = \"crank.rx\"\nvalue = 1.0\n",
                    "load: not part of a multibody model: apply forces with [[force]]");
  check_parse_error(kPlanar + "[[constraint]]\nterms = { a = 1.0 }\n",
                    "constraint: not part of a multibody model");
  check_parse_error(
      kPlanar + "[initial]\ndisplacement = { x = 1.0 }\n",
      "initial.displacement: a mechanism's initial poses and velocities are its [[body]]");
  check_parse_error(kPlanar + "[initial]\nkeep = [\"crank.x\"]\n",
                    "initial.keep: keeps values while [initial] project = true moves the others");
  check_parse_error(kPlanar + "[initial]\nproject = true\nkeep = [\"crank.qw\"]\n",
                    "initial.keep[1]: 'qw' is no value of body 'crank'");
  check_parse_error(
      replace(kSpatial, "[solve]", "[initial]\nproject = true\nkeep = [\"door.qx\"]\n[solve]"),
      "initial.keep[1]: 'door.qx' is one component of a quaternion");
  check_parse_error(
      kPlanar + "[initial]\nproject = true\nkeep = [\"crank.angel\"]\n",
      "initial.keep[1]: 'angel' is no value of body 'crank' that can be kept (did you "
      "mean angle?");
  check_parse_error(kPlanar + "[initial]\nproject = true\nkeep = [\"crnk.x\"]\n",
                    "initial.keep[1]: unknown body 'crnk' (did you mean crank?)");
  check_parse_error(kPlanar + "[initial]\nproject = true\nkeep = [\"crank.x\", \"crank.x\"]\n",
                    "initial.keep[2]: 'crank.x' is listed twice");
  check_parse_error(kPlanar + "[output]\npoints = [\"crank.Q\"]\n",
                    "output.points[1]: unknown point 'Q' of body 'crank' (known: A, B)");
  check_parse_error(kPlanar + "[output]\npoints = [\"ground.O\"]\n",
                    "output.points[1]: the ground's points do not move");
  check_parse_error(kPlanar + "[output]\npoints = [\"crankB\"]\n",
                    "output.points[1]: 'crankB' is not body.point");
  const std::string truss = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0]]
masses = [1.0]
members = []
[solve]
t_end = 1.0
output_step = 0.1
)";
  check_parse_error(truss + "[[body]]\nname = \"a\"\n", "body: [[body]] belongs to a mechanism");
  check_parse_error(truss + "[output]\npoints = [\"a.b\"]\n",
                    "output.points: names points of a mechanism");
  check_parse_error(replace(kPlanar, "[[body]]\nname = \"crank\"", "[[bodyy]]\nname = \"crank\""),
                    "bodyy: unknown key");
}

}  // namespace test_read_mechanism
