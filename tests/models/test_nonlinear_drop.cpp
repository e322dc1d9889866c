// Issue 44, item 7: [solve] redundant = "drop" on nonlinear rows. The system restricted to the
// kept rows (models/systems/row_subset_system.hpp) against the system it wraps and finite
// differences; a parallelogram four-bar with a redundant fifth bar run under GGL, index1, index3
// and projection against the same mechanism without the bar; the refusal without drop.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "models/systems/row_subset_system.hpp"
#include "tests/solve_helpers.hpp"
#include "tests/system_check.hpp"

using namespace condyn;

namespace test_nonlinear_drop {

namespace {

std::string redundant_scene() {
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) +
                   "/models/scenes/parallelogram_redundant_bar.toml");
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

/// The fifth bar EF of the scene, as written.
const std::string kFifthBar = "  { nodes = [6, 5], rigid = true },\n";

/// The same mechanism without the fifth bar: independent rows, nothing to drop.
std::string without_fifth_bar() { return replaced(redundant_scene(), kFifthBar, ""); }

/// The scene's nodes and rigid members (1-based, as written): the lengths every row holds.
constexpr std::array<std::array<double, 2>, 6> kNodes = {
    {{0.0, 0.0}, {0.0, 1.0}, {4.0, 1.0}, {4.0, 0.0}, {2.0, 3.0}, {2.0, 2.0}}};
constexpr std::array<std::array<int, 2>, 6> kMembers = {
    {{1, 2}, {2, 3}, {3, 4}, {2, 5}, {3, 5}, {6, 5}}};

int dof(const Model& model, const std::string& name) {
  for (std::size_t k = 0; k < model.dof_names.size(); ++k) {
    if (model.dof_names[k] == name) return static_cast<int>(k);
  }
  FAIL("no DOF " << name);
  return -1;
}

/// The largest |length − initial length| of the scene's members over the trajectory: the dropped
/// bar's too, which no row of the run holds any more.
double worst_length_error(const Model& model, const Trajectory& traj) {
  double worst = 0.0;
  for (const auto& [i, j] : kMembers) {
    const auto& xi = kNodes[static_cast<std::size_t>(i - 1)];
    const auto& xj = kNodes[static_cast<std::size_t>(j - 1)];
    const double length = std::hypot(xj[0] - xi[0], xj[1] - xi[1]);
    const auto row = [&](const std::string& axis, int node) {
      return traj.u.row(dof(model, "u" + axis + std::to_string(node))).array();
    };
    const Eigen::ArrayXd dx = xj[0] - xi[0] + row("x", j) - row("x", i);
    const Eigen::ArrayXd dy = xj[1] - xi[1] + row("y", j) - row("y", i);
    worst = std::max(worst, ((dx.square() + dy.square()).sqrt() - length).abs().maxCoeff());
  }
  return worst;
}

/// The exact motion: the coupler translates, every point of it on a unit circle about its pivot
/// (B = A + (cos θ, sin θ)), so B, C and F move alike and the crank angle obeys
/// 3 θ'' = −3 g cos θ (kinetic energy 3/2 θ'², potential 3 g sin θ), θ(0) = π/2, θ'(0) = π/2
/// (the scene's u'(0) = −π/2 along x). Integrated by classical Runge-Kutta at steps of 1e-4 s,
/// whose error (h⁴ times θ's fifth derivative, about 1e3 here) is 1e-13, far below the runs'.
double exact_angle(double t) {
  constexpr double kG = 9.81, kStep = 1e-4;
  const auto rate = [](const Eigen::Vector2d& y) {
    return Eigen::Vector2d(y[1], -kG * std::cos(y[0]));
  };
  Eigen::Vector2d y(std::numbers::pi / 2, std::numbers::pi / 2);
  const int steps = static_cast<int>(std::lround(t / kStep));
  for (int k = 0; k < steps; ++k) {
    const Eigen::Vector2d k1 = rate(y), k2 = rate(y + 0.5 * kStep * k1),
                          k3 = rate(y + 0.5 * kStep * k2), k4 = rate(y + kStep * k3);
    y += kStep / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return y[0];
}

/// The largest |u − u_exact| of the masses B, C, F over the output rows.
double motion_error(const Model& model, const Trajectory& traj) {
  double worst = 0.0;
  for (std::size_t k = 0; k < traj.t.size(); ++k) {
    const double theta = exact_angle(traj.t[k]);
    for (const char* node : {"2", "3", "5"}) {
      const auto col = static_cast<Eigen::Index>(k);
      worst = std::max(
          {worst, std::abs(traj.u(dof(model, std::string("ux") + node), col) - std::cos(theta)),
           std::abs(traj.u(dof(model, std::string("uy") + node), col) - (std::sin(theta) - 1.0))});
    }
  }
  return worst;
}

/// A run with rows dropped against the four-bar's under the same scheme: about as close to the
/// exact motion, and so within the sum of both errors of the four-bar's trajectory. Another set of
/// rows changes the steps and orders IDA takes: index3's error (150 rtol here: its error test
/// leaves velocities and multipliers out) moved by a factor 2.1 between two subsets, the other
/// schemes' by less; a factor 4 leaves margin and still fails a run that lost a constraint (its
/// error is of the motion's own size, 1). 10 rtol: a run far more accurate than its rtol.
void check_same_motion(const Model& model, const Trajectory& run, const Trajectory& four_bar,
                       double rtol) {
  const double error = motion_error(model, run), reference = motion_error(model, four_bar);
  const double apart = (run.u - four_bar.u).cwiseAbs().maxCoeff();
  MESSAGE("off the exact motion by " << error << " (four-bar " << reference << "), apart "
                                     << apart);
  CHECK(error <= 4.0 * reference + 10.0 * rtol);
  CHECK(apart <= error + reference);
}

/// Every member's length, the dropped one's too, held as the four-bar holds its own: within 10
/// times the four-bar run's worst length error, or 10 rtol times the 4 m coupler (what rtol asks
/// of positions on this mechanism), whichever is larger.
void check_lengths(const Model& model, const Trajectory& run, const Trajectory& four_bar,
                   double rtol) {
  CHECK(worst_length_error(model, run) <=
        10.0 * std::max(worst_length_error(model, four_bar), 4.0 * rtol));
}

}  // namespace

TEST_CASE("a system restricted to some rows is the wrapped one's rows, derivatives exact") {
  const test::BuiltScene full = test::built(parse_scene_text(without_fifth_bar(), "p.toml"));
  REQUIRE(full.model.is_nonlinear());
  const int n = full.model.dofs(), m = full.model.constraint_count();
  const std::vector<int> kept = {0, 2, 3, 5, 6, 8, m - 1};  // a support dropped, two rods
  RowSubsetSystem subset(*full.model.system, kept);
  REQUIRE(subset.constraints() == static_cast<int>(kept.size()));
  const Eigen::VectorXd u = full.model.u0 + 0.05 * Eigen::VectorXd::LinSpaced(n, -1.0, 1.3);
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n, 0.7, -0.4);
  const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(n, -1.1, 0.9);
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(subset.constraints(), 0.8, -1.7);
  for (const auto& problem : test::check_system_derivatives(subset, 0.3, u, v, a, w))
    FAIL_CHECK(problem);

  // Row k of every row block is the wrapped system's row kept[k], exactly (a copy of it).
  const auto inner = full.model.evaluator();
  Eigen::SparseMatrix<double> select(subset.constraints(), m);
  Eigen::VectorXd w_full = Eigen::VectorXd::Zero(m);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    select.insert(static_cast<Eigen::Index>(k), kept[k]) = 1.0;
    w_full[kept[k]] = w[static_cast<Eigen::Index>(k)];
  }
  const auto same = [](const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
    return x.rows() == y.rows() && x.cols() == y.cols() && x == y;
  };
  CHECK(same(subset.constraint_jacobian(0.3, u), select * inner->constraint_jacobian(0.3, u)));
  CHECK(same(subset.constraint_product_jacobian(0.3, u, a),
             select * inner->constraint_product_jacobian(0.3, u, a)));
  CHECK(same(subset.velocity_residual_jacobian(0.3, u, v),
             select * inner->velocity_residual_jacobian(0.3, u, v)));
  CHECK(same(subset.acceleration_bias_jacobian_v(0.3, u, v),
             select * inner->acceleration_bias_jacobian_v(0.3, u, v)));
  CHECK(same(subset.constraint_force_jacobian(0.3, u, w),
             inner->constraint_force_jacobian(0.3, u, w_full)));
  Eigen::VectorXd mine(subset.constraints()), theirs(m);
  subset.position_residual(0.3, u, mine);
  inner->position_residual(0.3, u, theirs);
  CHECK(same(mine, select * theirs));
  subset.velocity_residual(0.3, u, v, mine);
  inner->velocity_residual(0.3, u, v, theirs);
  CHECK(same(mine, select * theirs));
  subset.acceleration_bias(0.3, u, v, mine);
  inner->acceleration_bias(0.3, u, v, theirs);
  CHECK(same(mine, select * theirs));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    CHECK(subset.position_rows()[k] == inner->position_rows()[static_cast<std::size_t>(kept[k])]);
  }
  // A clone evaluates alike.
  const auto copy = subset.clone();
  CHECK(same(copy->constraint_jacobian(0.3, u), subset.constraint_jacobian(0.3, u)));

  for (const std::vector<int>& bad : {std::vector<int>{2, 1}, std::vector<int>{0, 0},
                                      std::vector<int>{-1}, std::vector<int>{m}}) {
    CHECK_THROWS_AS(RowSubsetSystem(*full.model.system, bad), std::invalid_argument);
  }
}

TEST_CASE("a parallelogram with a redundant fifth bar drops one row and runs like the four-bar") {
  // Before: refused at t = 0 ("drop does not apply to nonlinear rows yet").
  const test::BuiltScene redundant = test::built(parse_scene_text(redundant_scene(), "r.toml"));
  const test::BuiltScene reference = test::built(parse_scene_text(without_fifth_bar(), "p.toml"));
  REQUIRE(redundant.report.dropped_constraints.size() == 1);
  const std::string& dropped = redundant.report.dropped_constraints.front();
  CAPTURE(dropped);
  CHECK(dropped.find("'rigid_") == 0);
  CHECK(dropped.find("; their reactions carry its force too: not unique)") != std::string::npos);
  REQUIRE(redundant.model.dropped_constraints.size() == 1);
  CHECK(reference.report.dropped_constraints.empty());
  // Six supports and six rods, one dropped; the reference has six supports and five rods.
  CHECK(redundant.model.constraint_count() == 11);
  CHECK(redundant.model.system->constraints() == 11);
  CHECK(reference.model.constraint_count() == 11);

  const double rtol = redundant.spec.solve.rtol;
  const double atol = redundant.spec.solve.atol;
  // The net constraint force on each mass is unique (M u'' − f): the reaction columns of B, C and
  // F agree to the same multiple of rtol times their size (about 30 N: gravity and the
  // centripetal force of the falling coupler).
  const double kSameForce = 100.0 * rtol;
  for (const Scheme scheme : {Scheme::ggl, Scheme::index1, Scheme::index3, Scheme::projection}) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult run =
        test::solved(redundant.model, test::under(redundant.spec.solve, scheme));
    const SolveResult ref =
        test::solved(reference.model, test::under(reference.spec.solve, scheme));
    const Trajectory& tr = run.trajectory;
    const Trajectory& tf = ref.trajectory;
    REQUIRE(tr.u.cols() == tf.u.cols());
    check_same_motion(redundant.model, tr, tf, rtol);
    double force_scale = 0.0, force_off = 0.0;
    for (const char* name : {"ux2", "uy2", "ux3", "uy3", "ux5", "uy5"}) {
      const int d = dof(redundant.model, name);
      force_scale = std::max(force_scale, tf.reaction.row(d).cwiseAbs().maxCoeff());
      force_off =
          std::max(force_off, (tr.reaction.row(d) - tf.reaction.row(d)).cwiseAbs().maxCoeff());
    }
    MESSAGE("mass reactions off by " << force_off << " of " << force_scale);
    CHECK(force_off <= kSameForce * force_scale);
    // The drift of the kept rows is the four-bar's under the same scheme (index1's grows at its
    // rate, the others hold the rows to atol); every member's length, the dropped one's included,
    // holds as well: a factor 10 above the four-bar's own, or atol, covers the step sequences
    // differing.
    const double drift_bound = 10.0 * std::max(ref.summary.max_drift_position, atol);
    MESSAGE("drift " << run.summary.max_drift_position << ", four-bar's "
                     << ref.summary.max_drift_position);
    CHECK(run.summary.max_drift_position <= drift_bound);
    check_lengths(redundant.model, tr, tf, rtol);
  }
}

TEST_CASE("without drop, the redundant fifth bar is refused naming the dependent rows") {
  const std::string text = replaced(redundant_scene(), "redundant = \"drop\"\n", "");
  try {
    (void)build_model(parse_scene_text(text, "r.toml"));
    FAIL("a dependent set was accepted");
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    CAPTURE(msg);
    CHECK(msg.find("r.toml:") == 0);
    CHECK(msg.find("are linearly dependent at the initial configuration (constraint matrix rank "
                   "11 < 12)") != std::string::npos);
    // The fifth bar and the crank and rocker it parallels are in the set.
    for (const char* row : {"'rigid_6_5'", "'rigid_1_2'", "'rigid_3_4'"}) {
      CHECK(msg.find(row) != std::string::npos);
    }
    CHECK(msg.find("set [solve] redundant = \"drop\" to drop it") != std::string::npos);
  }
}

TEST_CASE("another independent subset of the redundant rows runs the same motion") {
  // The rank check drops the fifth bar itself (the last row in pivot order), which leaves the
  // four-bar's rows exactly. Kept instead: the fifth bar, without the crank, through the same
  // RowSubsetSystem on the scene's every row; the motion is the four-bar's to rtol.
  const test::BuiltScene redundant = test::built(parse_scene_text(redundant_scene(), "r.toml"));
  const test::BuiltScene reference = test::built(parse_scene_text(without_fifth_bar(), "p.toml"));
  const auto* built = dynamic_cast<const RowSubsetSystem*>(redundant.model.system.get());
  REQUIRE(built != nullptr);
  const MechanicalSystem& every_row = built->wrapped();
  // Rows: six supports, then the rods as written, the fifth bar (rigid_6_5) last.
  const int m = every_row.constraints();
  REQUIRE(m == 12);
  REQUIRE(redundant.model.constraints[6].name == "rigid_1_2");
  std::vector<int> kept;
  for (int r = 0; r < m; ++r) {
    if (r != 6) kept.push_back(r);
  }
  Model other = redundant.model;
  other.system = std::make_shared<RowSubsetSystem>(every_row, kept);
  Constraint fifth = other.constraints[6];
  fifth.name = "rigid_6_5";
  other.constraints.erase(other.constraints.begin() + 6);
  other.constraints.push_back(fifth);
  other.A = other.evaluator()->constraint_jacobian(0.0, other.u0);
  other.A.prune(0.0);
  const double rtol = redundant.spec.solve.rtol;
  for (const Scheme scheme : {Scheme::ggl, Scheme::index1, Scheme::index3, Scheme::projection}) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult run = test::solved(other, test::under(redundant.spec.solve, scheme));
    const SolveResult ref =
        test::solved(reference.model, test::under(reference.spec.solve, scheme));
    check_same_motion(other, run.trajectory, ref.trajectory, rtol);
    check_lengths(other, run.trajectory, ref.trajectory, rtol);
  }
}

TEST_CASE("a mechanism's joints are listed with the rows kept after redundant = \"drop\"") {
  BuildReport report;
  const Model model = build_model(
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/iftomm/A04_bricard.toml"),
      report);
  REQUIRE(model.dropped_constraints == std::vector<std::string>{"J2.x"});
  // The joint the rank check dropped a row of: its remaining rows, then the one dropped.
  REQUIRE(report.joints.size() == 6);
  CHECK(report.joints[1].find("J2 (revolute, link1 - link2): 4 rows (J2.y, J2.z, J2.axis_b, "
                              "J2.axis_c), 1 dropped as redundant (J2.x), holonomic") == 0);
  // Every joint's line names exactly the model's rows of that joint, and its dropped ones.
  std::size_t dropped_listed = 0;
  for (const std::string& line : report.joints) {
    CAPTURE(line);
    const std::string joint = line.substr(0, line.find(' '));
    std::vector<std::string> kept, dropped;
    for (const auto& c : model.constraints)
      if (c.name.rfind(joint + ".", 0) == 0) kept.push_back(c.name);
    for (const auto& d : model.dropped_constraints)
      if (d.rfind(joint + ".", 0) == 0) dropped.push_back(d);
    const auto listed = [](const std::vector<std::string>& names) {
      std::string text;
      for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
      return "(" + text + ")";
    };
    const std::string rows = kept.size() == 1 ? " row " : " rows ";
    CHECK(line.find(": " + std::to_string(kept.size()) + rows + listed(kept)) != std::string::npos);
    CHECK((line.find("dropped as redundant " + listed(dropped)) != std::string::npos) ==
          !dropped.empty());
    dropped_listed += dropped.size();
  }
  CHECK(dropped_listed == model.dropped_constraints.size());
}

}  // namespace test_nonlinear_drop
