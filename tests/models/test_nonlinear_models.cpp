// The nonlinear models of issue 5: point masses with rigid members and large-displacement bars,
// the Chaplygin sleigh. Derivatives against finite differences, the formulations' Jacobians with
// the curvature blocks, the initial projection, and the refusals.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "dae/formulations/multiplier_dae.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/classification.hpp"
#include "models/core/constraint_drift.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/compare.hpp"
#include "tests/scene_errors.hpp"
#include "tests/solve_helpers.hpp"
#include "tests/system_check.hpp"

using namespace condyn;

namespace test_nonlinear_models {

using condyn::test::build_error;

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();

test::BuiltScene scene(const std::string& name) { return test::built(test::shipped_scene(name)); }

/// A generic state: u0 plus a perturbation, nonzero velocities, accelerations and multipliers.
struct State {
  Eigen::VectorXd u, v, a, w;
};
State generic_state(const Model& model) {
  const int n = model.dofs(), m = model.constraint_count();
  State s;
  s.u = model.u0 + 0.05 * Eigen::VectorXd::LinSpaced(n, -1.0, 1.3);
  s.v = Eigen::VectorXd::LinSpaced(n, 0.7, -0.4);
  s.a = Eigen::VectorXd::LinSpaced(n, -1.1, 0.9);
  s.w = Eigen::VectorXd::LinSpaced(m, 0.8, -1.7);
  return s;
}

const char* kNonlinearScenes[] = {"pendulum.toml",         "double_pendulum.toml",
                                  "four_bar.toml",         "hanging_chain.toml",
                                  "von_mises_truss.toml",  "spherical_pendulum.toml",
                                  "chaplygin_sleigh.toml", "damped_spring_pendulum.toml"};

}  // namespace

TEST_CASE("nonlinear scenes: every derivative agrees with finite differences") {
  for (const char* name : kNonlinearScenes) {
    CAPTURE(std::string(name));
    const Model model = scene(name).model;
    REQUIRE(model.is_nonlinear());
    const State s = generic_state(model);
    const auto problems = test::check_system_derivatives(*model.system, 0.3, s.u, s.v, s.a, s.w);
    for (const auto& p : problems) FAIL_CHECK(p);
    CHECK(problems.empty());
  }
}

TEST_CASE("multiplier formulations with curvature: Jacobian agrees with central differences") {
  for (const char* name :
       {"double_pendulum.toml", "chaplygin_sleigh.toml", "von_mises_truss.toml"}) {
    const Model model = scene(name).model;
    for (auto scheme :
         {Scheme::index1, Scheme::baumgarte, Scheme::ggl, Scheme::index2, Scheme::index3}) {
      CAPTURE(std::string(name));
      CAPTURE(static_cast<int>(scheme));
      const MultiplierDae dae(*model.system, scheme, 0.7, 1.3);
      const int n = dae.size();
      Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(n, 0.3, -0.7);
      y.head(model.dofs()) += model.u0;
      const Eigen::VectorXd yp = Eigen::VectorXd::LinSpaced(n, -0.2, 0.9);
      const double t = 0.37, cj = 12.5;
      Eigen::SparseMatrix<double> J = dae.jacobian_pattern().matrix();
      dae.jacobian(t, y, yp, cj, J);
      // Nonlinear residual: central differences with h = 1e-6 are accurate to ~h² |F'''| + eps/h.
      CONDYN_CHECK_CLOSE(Eigen::MatrixXd(J), test::finite_difference_jacobian(dae, t, y, yp, cj),
                         1e-6);
    }
  }
}

TEST_CASE("Chaplygin sleigh: nonholonomic, refused by elimination with the chapter's reason") {
  const test::BuiltScene built = scene("chaplygin_sleigh.toml");
  const Model& model = built.model;
  const auto classes = classify_constraints(model, built.spec.solve.t_end);
  REQUIRE(classes.size() == 1);
  CHECK(classes[0].holonomy() == "nonholonomic");
  CHECK_FALSE(classes[0].linear);
  // a = (−sin θ, cos θ, a): a · (∇ × a) = −1 at every state.
  CHECK(classes[0].note.find("1 != 0, not integrable") != std::string::npos);
  const auto why = scheme_refusal(model, Scheme::elimination);
  REQUIRE(why);
  CHECK(why->find("nonholonomic") != std::string::npos);
  CHECK(why->find("§5.6") != std::string::npos);
  CHECK_THROWS_AS((void)solve(model, test::under(built.spec.solve, Scheme::elimination)),
                  std::invalid_argument);
  CHECK(choose_scheme(model, test::under(built.spec.solve, Scheme::automatic)).scheme ==
        Scheme::ggl);
}

TEST_CASE("Chaplygin sleigh with the edge at the centre of mass: exact circular motion") {
  // With a = 0 the constraint force does no work and exerts no moment: θ' and the forward speed
  // s = cos θ x' + sin θ y' stay constant, so the centre of mass runs on a circle of radius s/ω:
  // x = (s/ω) sin(ωt), y = (s/ω)(1 − cos(ωt)) from x = y = θ = 0, x' = s, y' = 0, θ' = ω.
  std::string text = R"([model]
type = "sleigh"
mass = 2.0
inertia = 0.3
contact_offset = 0.0
[initial]
velocity = { x = 1.5, theta = 0.8 }
[solve]
t_end = 10.0
output_step = 0.5
rtol = 1e-10
atol = 1e-12
)";
  const SceneSpec spec = parse_scene_text(text, "sleigh");
  const Model model = build_model(spec);
  const double s = 1.5, w = 0.8;
  for (Scheme scheme : {Scheme::index1, Scheme::baumgarte, Scheme::ggl, Scheme::index2,
                        Scheme::index3, Scheme::projection}) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult result = test::solved(model, test::under(spec.solve, scheme));
    const Trajectory& traj = result.trajectory;
    const SolveSummary& summary = result.summary;
    double err = 0.0;
    for (std::size_t k = 0; k < traj.t.size(); ++k) {
      const double t = traj.t[k];
      const Eigen::Vector3d exact(s / w * std::sin(w * t), s / w * (1.0 - std::cos(w * t)), w * t);
      err = std::max(err, (traj.u.col(static_cast<Eigen::Index>(k)) - exact).cwiseAbs().maxCoeff());
    }
    // rtol 1e-10 over 10 s, absolute error with |u| ≤ 8: kGlobalErrorFactor (1e3) × rtol × 8
    // (observed up to 2.2e-8), except under index3, which leaves the velocities out of the error
    // test (index 2 there) and is the least accurate per tolerance (docs/schemes.md): ten times
    // that (observed 1.3e-6; 2.7e-6 before). The velocity constraint (|v| ≈ 1.5 m/s) is held to
    // the same factors × rtol: observed up to 5.1e-9, index3 1.1e-7.
    CHECK(err < (scheme == Scheme::index3 ? 1e4 : 1e3) * 1e-10 * 8.0);
    CHECK(summary.max_drift_velocity < (scheme == Scheme::index3 ? 1e4 : 1e3) * 1e-10);
  }
}

TEST_CASE("initial projection: the four-bar's crank speed becomes a consistent state") {
  const test::BuiltScene four_bar = scene("four_bar.toml");
  const Model& model = four_bar.model;
  CHECK(four_bar.report.initial_projection.find("projected") != std::string::npos);
  const auto [dp, dv] = ConstraintDrift(model)(0.0, model.u0, model.v0);
  // The projected state is consistent to roundoff: a few ulps of the O(1) lengths and of the
  // speeds (|v| ≤ 6): 8 eps × scale (observed 3.3e-16 and 1.5e-15).
  CHECK(dp < 8 * kEps);
  CHECK(dv < 8 * kEps * 6.0);
  // The supports stay put (to roundoff of the speeds, observed 1.9e-16); the crank keeps most of
  // its speed.
  CHECK(model.v0.head(2).cwiseAbs().maxCoeff() < 8 * kEps * 6.0);
  CHECK(std::abs(model.v0[2]) > 1.0);

  // Without project = true the same start is refused, naming the constraint and the remedy.
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/four_bar.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.rfind("project = true");  // the key, not the comment
  REQUIRE(at != std::string::npos);
  text.replace(at, 14, "project = false");
  const std::string error = build_error(text);
  CHECK(error.find("initial velocities violate constraint 'rigid_2_3'") != std::string::npos);
  CHECK(error.find("project = true") != std::string::npos);
}

TEST_CASE("nonlinear scene errors name the key and the problem") {
  const std::string head = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
)";
  const std::string tail = R"(
[solve]
t_end = 1.0
output_step = 0.1
)";
  CHECK(build_error(head + "members = [{ nodes = [1, 2], rigid = true, EA = 5.0 }]\n" + tail)
            .find("model.members[1].EA: a rigid member has no stiffness") != std::string::npos);
  CHECK(build_error(head + "members = [{ nodes = [1, 2], rigid = true }]\ngravity = [0.0]\n" + tail)
            .find("model.gravity: needs 2 components") != std::string::npos);
  CHECK(build_error(head + "members = [{ nodes = [1, 2], EA = 1.0 }]\ngeometry = \"big\"\n" + tail)
            .find("model.geometry: expected 'linear' or 'nonlinear'") != std::string::npos);
  CHECK(build_error(R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [3]
members = [{ nodes = [1, 2], rigid = true }]
)" + tail)
            .find("model.supports[1]: node 3 does not exist") != std::string::npos);
  CHECK(build_error("[model]\ntype = \"sleigh\"\ninertia = 1.0\n" + tail)
            .find("model.mass: missing required key") != std::string::npos);
  CHECK(build_error("[model]\ntype = \"andrews\"\n[[load]]\ndof = \"beta\"\nvalue = 1.0\n" + tail)
            .find("fixes its own forces") != std::string::npos);
  CHECK(build_error("[model]\ntype = \"pendulum\"\nmass = 2.0\n" + tail)
            .find("model.mass: unknown key") != std::string::npos);
  // An initial displacement that stretches a rigid member.
  CHECK(build_error(head +
                    "members = [{ nodes = [1, 2], rigid = true }]\n[initial]\n"
                    "displacement = { ux2 = 0.1 }\n" +
                    tail)
            .find("initial displacements violate constraint 'rigid_1_2'") != std::string::npos);
}

TEST_CASE("a benchmark started away from its published state has no reference") {
  const std::string scene = R"([model]
type = "pendulum"
[solve]
t_end = 2.0
output_step = 1.0
)";
  const Model published = build_model(parse_scene_text(scene, "p"));
  REQUIRE(published.reference);
  CHECK(published.reference(2.0).has_value());
  // A tangential push keeps the start consistent, but the period-2 orbit is gone.
  const Model pushed =
      build_model(parse_scene_text(scene + "[initial]\nvelocity = { y = 0.5 }\n", "p"));
  CHECK_FALSE(pushed.reference);
  CHECK(pushed.description.find("no reference") != std::string::npos);
}

}  // namespace test_nonlinear_models
