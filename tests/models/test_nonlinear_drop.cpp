// Issue 44, item 7: [solve] redundant = "drop" on nonlinear rows. The system restricted to the
// kept rows (models/systems/row_subset_system.hpp) against the system it wraps and finite
// differences; a parallelogram four-bar with a redundant fifth bar run under GGL, index1, index3
// and projection against the same mechanism without the bar; the refusal without drop.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "models/systems/row_subset_system.hpp"
#include "tests/solve_helpers.hpp"
#include "tests/system_check.hpp"

using namespace condyn;

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
  // Both runs integrate the same motion (lengths of 1 to 4, speeds of π/2) at rtol, each with its
  // own global error of a few rtol over the half second: their difference is bounded by a
  // multiple of rtol times the size of the motion (1), with margin for accumulation.
  const double kSameMotion = 100.0 * rtol;
  // The net constraint force on each mass is unique (M u'' − f): the reaction columns of B, C and
  // F agree to the same multiple of rtol times their size (about 30 N: gravity and the
  // centripetal force of the falling coupler).
  const double kSameForce = 100.0 * rtol;
  for (const Scheme scheme : {Scheme::ggl, Scheme::index1, Scheme::index3, Scheme::projection}) {
    CAPTURE(to_string(scheme));
    const SolveResult run =
        test::solved(redundant.model, test::under(redundant.spec.solve, scheme));
    const SolveResult ref =
        test::solved(reference.model, test::under(reference.spec.solve, scheme));
    const Trajectory& tr = run.trajectory;
    const Trajectory& tf = ref.trajectory;
    REQUIRE(tr.u.cols() == tf.u.cols());
    const double motion = (tr.u - tf.u).cwiseAbs().maxCoeff();
    MESSAGE("u off the four-bar by " << motion);
    CHECK(motion <= kSameMotion);
    double force_scale = 0.0, force_off = 0.0;
    for (const char* name : {"ux2", "uy2", "ux3", "uy3", "ux5", "uy5"}) {
      const int d = dof(redundant.model, name);
      force_scale = std::max(force_scale, tf.reaction.row(d).cwiseAbs().maxCoeff());
      force_off = std::max(force_off, (tr.reaction.row(d) - tf.reaction.row(d)).cwiseAbs().maxCoeff());
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
    CHECK(worst_length_error(redundant.model, tr) <=
          10.0 * std::max(worst_length_error(reference.model, tf), atol));
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
