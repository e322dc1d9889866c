// Accelerations as an output quantity (issue 13): u'' from the equations of motion at each output
// row, M u'' = f + f_con, under every scheme, whole or streamed.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_accelerations {

namespace {

/// m = 2, k = 8, u0 = 1: u'' = −4 u.
std::string oscillator(const std::string& scheme) {
  return R"([model]
type = "matrix"
dofs = ["x"]
mass = [[2.0]]
stiffness = [[8.0]]
[initial]
displacement = { x = 1.0 }
[solve]
t_end = 3.0
output_step = 0.1
rtol = 1e-8
atol = 1e-10
scheme = ")" +
         scheme + "\"\n";
}

RunHooks with_accelerations() {
  RunHooks hooks;
  hooks.accelerations = true;
  return hooks;
}

/// max over rows of |M a + C v + K u − f(t) − f_con| / max(|K u|, |f|, |f_con|, 1).
double equation_residual(const Model& model, const Trajectory& traj) {
  double worst = 0.0;
  for (std::size_t k = 0; k < traj.t.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    const Eigen::VectorXd ku = *model.K * traj.u.col(col);
    const Eigen::VectorXd f = model.applied_forces(traj.t[k]);
    Eigen::VectorXd r = model.M * traj.acceleration.col(col) + ku - f - traj.reaction.col(col);
    if (model.has_damping()) r += model.C * traj.v.col(col);
    const double scale = std::max({ku.cwiseAbs().maxCoeff(), f.cwiseAbs().maxCoeff(),
                                   traj.reaction.col(col).cwiseAbs().maxCoeff(), 1.0});
    worst = std::max(worst, r.cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

}  // namespace

TEST_CASE("accelerations of a single oscillator: u'' = −(k/m) u at every output, every scheme") {
  for (const char* scheme : {"elimination", "index1", "ggl", "projection", "penalty"}) {
    CAPTURE(scheme);
    const auto s = test::built(parse_scene_text(oscillator(scheme), "osc.toml"));
    const SolveResult r = test::solved(s.model, s.spec.solve, with_accelerations());
    const Trajectory& traj = r.trajectory;
    REQUIRE(traj.acceleration.rows() == 1);
    REQUIRE(traj.acceleration.cols() == static_cast<Eigen::Index>(traj.t.size()));
    for (std::size_t k = 0; k < traj.t.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      CAPTURE(traj.t[k]);
      // Exact from the equation (one division): a few ulps of |4u| <= 4.
      CHECK(std::abs(traj.acceleration(0, col) + 4.0 * traj.u(0, col)) <= 1e-14);
      // And against the exact solution, −4 cos 2t, to the run's accuracy.
      CHECK(std::abs(traj.acceleration(0, col) + 4.0 * std::cos(2.0 * traj.t[k])) <= 1e-5);
    }
  }
}

TEST_CASE("accelerations are computed only when asked for") {
  const auto s = test::built(parse_scene_text(oscillator("index1"), "osc.toml"));
  CHECK(test::solved(s.model, s.spec.solve).trajectory.acceleration.size() == 0);
}

TEST_CASE("accelerations satisfy M a + C v + K u = f + f_con at every row, under every scheme") {
  // The two masses, a tied to 0, with damping on b; the tie's row makes a'' = 0.
  const std::string base = test::replace(test::kTwoMassesScene, "output_step = 0.25\n",
                                         "output_step = 0.05\nrtol = 1e-8\natol = 1e-10\n");
  const std::string damped = test::replace(base, "stiffness = [[3.0, -1.0], [-1.0, 1.0]]\n",
                                           "stiffness = [[3.0, -1.0], [-1.0, 1.0]]\n"
                                           "damping = [[0.0, 0.0], [0.0, 0.1]]\n");
  struct Case {
    const char* scheme;
    const char* extra;
  };
  for (const Case c :
       {Case{"elimination", ""}, Case{"index1", ""}, Case{"baumgarte", ""}, Case{"ggl", ""},
        Case{"index2", ""}, Case{"index3", ""}, Case{"penalty", ""}, Case{"projection", ""},
        Case{"ggl", "constraints = \"mixed\"\n"}, Case{"index1", "constraints = \"mixed\"\n"}}) {
    CAPTURE(c.scheme);
    CAPTURE(c.extra);
    const std::string text = damped + "scheme = \"" + c.scheme + "\"\n" + c.extra;
    const auto s = test::built(parse_scene_text(text, "two.toml"));
    const SolveResult r = test::solved(s.model, s.spec.solve, with_accelerations());
    const Trajectory& traj = r.trajectory;
    REQUIRE(traj.acceleration.cols() == static_cast<Eigen::Index>(traj.t.size()));
    CHECK(equation_residual(s.model, traj) <= 1e-12);
    // The tie holds a at 0: its acceleration vanishes to roundoff, as every multiplier scheme's
    // rows take λ from acceleration level (dae/formulations/row_multipliers.hpp; before, index2's
    // and index3's own λ left it at 1e-3 of b's); penalty's spring lets a move.
    const std::string scheme = c.scheme;
    if (scheme != "penalty") {
      const double scale = traj.acceleration.row(1).cwiseAbs().maxCoeff();
      CHECK(traj.acceleration.row(0).cwiseAbs().maxCoeff() <= 1e-12 * scale);
    }

    // Streamed rows carry the same accelerations.
    std::vector<Eigen::VectorXd> streamed;
    RunHooks hooks = with_accelerations();
    hooks.on_row = [&](const TrajectoryRow& row) { streamed.push_back(row.acceleration); };
    (void)test::solved(s.model, s.spec.solve, hooks);
    REQUIRE(streamed.size() == traj.t.size());
    for (std::size_t k = 0; k < streamed.size(); ++k) {
      CHECK((streamed[k] - traj.acceleration.col(static_cast<Eigen::Index>(k)))
                .cwiseAbs()
                .maxCoeff() == doctest::Approx(0.0));
    }
  }
}

TEST_CASE("accelerations of massless DOFs in constraints come from the constraints") {
  // The pendulum's support node has no mass and its DOFs are fixed: 0.
  {
    const auto s = test::built(parse_scene_text(
        test::pendulum_scene("t_end = 0.5\noutput_step = 0.1\nscheme = \"ggl\"\n"), "p.toml"));
    const Trajectory traj = test::solved(s.model, s.spec.solve, with_accelerations()).trajectory;
    for (const char* dof : {"ux1", "uy1"}) {
      const auto d = static_cast<Eigen::Index>(s.model.dof_at(dof));
      CHECK(traj.acceleration.row(d).cwiseAbs().maxCoeff() == 0.0);
    }
    // The bob starts from rest with the rod horizontal: it falls at g.
    const auto uy2 = static_cast<Eigen::Index>(s.model.dof_at("uy2"));
    CHECK(traj.acceleration(uy2, 0) == doctest::Approx(-9.81).epsilon(1e-6));
  }
  // A massless node driven along x, ux1 = 0.1 sin 3t (a nonlinear model: its rod): its
  // acceleration is the drive's, −0.9 sin 3t, from the row at acceleration level, to roundoff.
  for (const char* scheme : {"ggl", "index1", "index3", "projection"}) {
    CAPTURE(scheme);
    const auto s = test::built(parse_scene_text(
        test::driven_pendulum_scene(std::string("scheme = \"") + scheme + "\"\n"), "d.toml"));
    const Trajectory traj = test::solved(s.model, s.spec.solve, with_accelerations()).trajectory;
    const auto ux1 = static_cast<Eigen::Index>(s.model.dof_at("ux1"));
    const auto uy1 = static_cast<Eigen::Index>(s.model.dof_at("uy1"));
    for (std::size_t k = 0; k < traj.t.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      CHECK(traj.acceleration(ux1, col) ==
            doctest::Approx(-0.9 * std::sin(3.0 * traj.t[k])).epsilon(1e-12).scale(1.0));
      CHECK(traj.acceleration(uy1, col) == 0.0);
    }
  }
}

}  // namespace test_accelerations
