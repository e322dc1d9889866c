#pragma once
/// Scene texts the tests share, and the edit they make to them: the same small models serve
/// the parser, CLI and integrator tests, so each is written once.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace condyn::test {

/// A wall, spring 200, mass 2 (u1), spring 200, mass 1 (u2): the [model] table alone, for tests
/// that add their own loads, constraints and [solve].
inline const std::string kTwoMassChainModel = R"([model]
type = "matrix"
dofs = ["u1", "u2"]
mass = [[2.0, 0.0], [0.0, 1.0]]
stiffness = [[400.0, -200.0], [-200.0, 200.0]]
)";

/// Four masses (1, 2, 1, 1) on a chain of springs 1, 1, 1 and a stiff 100 between c and d: the
/// [model] table alone.
inline const std::string kFourMassModel = R"([model]
type = "matrix"
dofs = ["a", "b", "c", "d"]
mass = [[1.0, 0.0, 0.0, 0.0], [0.0, 2.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
stiffness = [[2.0, -1.0, 0.0, 0.0], [-1.0, 2.0, -1.0, 0.0], [0.0, -1.0, 101.0, -100.0], [0.0, 0.0, -100.0, 100.0]]
)";

/// kFourMassModel with rows 1e150 apart in scale: a support a = 0, a tie written at 1e-150,
/// 1e-150 (b − c) = 1e-151 sin 2t, and d + 1e-15 c = 0; a step load on c at 0.5, b moving at 0.2.
/// Its [solve] table is open after output_step (t_end 1, steps of 0.1).
inline const std::string kScaledTieScene = kFourMassModel + R"([[constraint]]
name = "support"
terms = { a = 1.0 }
[[constraint]]
name = "tie"
terms = { b = 1e-150, c = -1e-150 }
value = { type = "harmonic", amplitude = 1e-151, omega = 2.0 }
[[constraint]]
name = "mix"
terms = { d = 1.0, c = 1e-15 }
[[load]]
dof = "c"
value = { type = "step", amplitude = 1.0, start = 0.5 }
[initial]
velocity = { b = 0.2 }
[solve]
t_end = 1.0
output_step = 0.1
)";

/// Two masses on springs, one tied by a constraint, a step load at t = 0.25; four output
/// intervals to t = 1 (the CLI tests' model).
inline const std::string kTwoMassesScene = R"(name = "two masses"
[model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 2.0]]
stiffness = [[3.0, -1.0], [-1.0, 1.0]]
[[load]]
dof = "b"
value = { type = "step", amplitude = 1.0, start = 0.25 }
[[constraint]]
name = "tie"
terms = { a = 1.0 }
[solve]
t_end = 1.0
output_step = 0.25
)";

/// A pendulum of unit length and mass released from rest with its rod horizontal, under
/// gravity, as a truss with a rigid member; `solve_keys` are the lines of its [solve] table.
inline std::string pendulum_scene(const std::string& solve_keys) {
  return R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }]
gravity = [0.0, -9.81]
[solve]
)" + solve_keys;
}

/// The pendulum above over 0.5 with the fixed step 0.01 (the Newmark family's and RATTLE's),
/// output every 0.05 of every quantity a constrained run writes.
inline const std::string kFixedStepPendulum = pendulum_scene(R"(t_end = 0.5
output_step = 0.05
step = 0.01
[output]
quantities = ["displacement", "velocity", "reaction", "multiplier", "drift", "energy"]
)");

/// A conical pendulum in exactly steady rotation (truss3d): a unit mass on a rigid member of
/// length L from a fixed support, at `degrees` from the vertical, gravity 9.81 L along −z (the
/// same motion in other length units: L = 1000 is millimetres), started with `speed` times the
/// steady speed ω r (ω² = 9.81 / cos a, r = L sin a); rtol 1e-8, output every 0.01.
inline std::string conical_pendulum_scene(double degrees, double t_end, double speed = 1.0,
                                          double atol = 1e-10, double length = 1.0) {
  constexpr double kG = 9.81;
  const double a = degrees * std::numbers::pi / 180.0;
  const double r = length * std::sin(a), z = -length * std::cos(a);
  const double w = std::sqrt(kG / std::cos(a));
  std::ostringstream s;
  s.precision(17);
  s << "[model]\ntype = \"truss3d\"\nnodes = [[0.0, 0.0, 0.0], [" << r << ", 0.0, " << z
    << "]]\nmasses = [0.0, 1.0]\nsupports = [1]\nmembers = [{ nodes = [1, 2], rigid = true }]\n"
       "gravity = [0.0, 0.0, "
    << -kG * length << "]\n[initial]\nvelocity = { uy2 = " << speed * w * r
    << " }\n[solve]\nt_end = " << t_end << "\noutput_step = 0.01\nrtol = 1e-8\natol = " << atol
    << "\n";
  return s.str();
}

/// The pendulum with a rheonomic row pulling its mass straight down at unit speed, under GGL to
/// t = 2: at t = 1 the rod is vertical, its row parallel to the pull's, and no motion satisfies
/// both beyond it. A run that fails midway, after ten output rows, its step size collapsed: its
/// steps shrink below 1e-13 (the collapse's bound is 1e-12 t) within 3,000 steps past t = 0.9 and
/// stay there, and 1,000 such steps in a row end the run (a dozen of these runs are in the tests,
/// under the sanitizers too).
inline const std::string kPulledPendulumScene = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }]
gravity = [0.0, -9.81]
[[constraint]]
name = "pull"
terms = { uy2 = 1.0 }
value = { type = "polynomial", coefficients = [0.0, -1.0] }
[initial]
velocity = { uy2 = -1.0 }
[solve]
t_end = 2.0
output_step = 0.1
scheme = "ggl"
)";

/// A pendulum (unit mass, rigid rod of length 1) hung from a massless node whose x is driven,
/// ux1 = 0.1 sin(3t), uy1 = 0: a nonlinear model with rheonomic linear rows.
inline std::string driven_pendulum_scene(const std::string& solve_keys) {
  return R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
members = [{ nodes = [1, 2], rigid = true }]
gravity = [0.0, -9.81]
[[constraint]]
name = "drive"
terms = { ux1 = 1.0 }
value = { type = "harmonic", amplitude = 0.1, omega = 3.0 }
[[constraint]]
name = "rail"
terms = { uy1 = 1.0 }
[initial]
velocity = { ux1 = 0.3, ux2 = 0.3 }
[solve]
t_end = 2.0
output_step = 0.1
)" + solve_keys;
}

/// A triangle pinned at node 1 whose node 3 has no mass: its two bars hold it (an algebraic DOF
/// pair, integrated by every scheme: docs/schemes.md, "Massless DOFs").
inline const std::string kMasslessTriangleScene = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
masses = [1.0, 1.0, 0.0]
members = [{ nodes = [1, 2], EA = 10.0 }, { nodes = [2, 3], EA = 10.0 }, { nodes = [1, 3], EA = 10.0 }]
supports = [1]

[solve]
t_end = 1.0
output_step = 0.5
)";

/// A chain of `links` rigid members (length `link`, a point mass `mass` at every joint) hanging
/// from a fixed support at node 1, released from rest along a straight line `degrees` below the
/// horizontal, under gravity 9.81: models/scenes/hanging_chain.toml (8 links of 0.5, 0.1 each, 30
/// degrees) for any number of links. Its [solve] table is open after scheme = "ggl" (t_end 1).
inline std::string hanging_chain_scene(int links, double link = 0.5, double mass = 0.1,
                                       double degrees = 30.0) {
  const double c = std::cos(degrees * std::numbers::pi / 180.0);
  const double s = std::sin(degrees * std::numbers::pi / 180.0);
  std::ostringstream o;
  o.precision(17);
  o << "[model]\ntype = \"truss2d\"\nnodes = [";
  for (int k = 0; k <= links; ++k)
    o << (k > 0 ? ", " : "") << "[" << k * link * c << ", " << -k * link * s << "]";
  o << "]\nmasses = [0.0";
  for (int k = 0; k < links; ++k) o << ", " << mass;
  o << "]\nsupports = [1]\nmembers = [";
  for (int k = 1; k <= links; ++k) {
    o << (k > 1 ? ", " : "") << "{ nodes = [" << k << ", " << k + 1 << "], rigid = true }";
  }
  o << "]\ngravity = [0.0, -9.81]\n[solve]\nt_end = 1.0\noutput_step = 0.1\nscheme = \"ggl\"\n";
  return o.str();
}

/// `s` with its first `from` replaced by `to`; fails the test when `from` is absent.
inline std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  REQUIRE_MESSAGE(pos != std::string::npos, from);
  return s.replace(pos, from.size(), to);
}

/// A crank's angle table (drive.csv of kTableDrivenCrank), samples at 0, 0.3, 0.55 and 1: slopes
/// 2, −2 and 2/3 rad/s, kinks at 0.3 (an output time), 0.55 (between two) and 1, held at 0.4 after
/// t = 1.
inline const std::string kCrankDriveTable = "t,angle\n0,0\n0.3,0.6\n0.55,0.1\n1.0,0.4\n";

/// A crank of length 1 and mass 1 hinged at its end O, driven by the table drive.csv
/// (kCrankDriveTable), under gravity (so that the drive carries a torque); it starts at the
/// table's first rate, 2 rad/s. Output every 0.1 to t = 1.2, rtol 1e-8, atol 1e-10.
inline const std::string kTableDrivenCrank = R"([model]
type = "multibody"
dimension = 2
gravity = [0.0, -9.81]
ground = { O = [0.0, 0.0] }
[[body]]
name = "crank"
mass = 1.0
inertia = 0.0833
position = [0.5, 0.0]
velocity = [0.0, 1.0]
angular_velocity = 2.0
points = { O = [-0.5, 0.0] }
[[joint]]
name = "pivot"
type = "revolute"
bodies = ["ground", "crank"]
points = ["O", "O"]
drive = { type = "table", file = "drive.csv", column = "angle" }
[solve]
t_end = 1.2
output_step = 0.1
rtol = 1e-8
atol = 1e-10
)";

/// Two masses on springs, the second tied to the first by a stiff spring (k = 1e6: ω ≈ 1.4e3
/// against the soft mode's ≈ 1), undamped, under a step load on the second: the stiff mode is
/// excited and never resolved at rtol 1e-6 over 10 s (models/scenes/stiff_pair.toml); `solve_keys`
/// after rtol and atol in [solve].
inline std::string stiff_pair_scene(const std::string& solve_keys) {
  return R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[1000001.0, -1000000.0], [-1000000.0, 1000000.0]]
[[load]]
dof = "b"
value = 1.0
[solve]
t_end = 10.0
output_step = 0.5
rtol = 1e-6
atol = 1e-9
)" + solve_keys;
}

}  // namespace condyn::test
