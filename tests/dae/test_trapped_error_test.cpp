// A conical pendulum in exactly steady rotation: a unit mass on a rigid member of length 1 from a
// fixed support, at angle a from the vertical, started with the steady speed ω r (ω² = g / (L cos
// a), r = L sin a). Its height u_z stays at 0, so its error weight is 1/atol, while the projection
// onto the member's row (GGL's μ, index3's φ = 0) hands it a share of the horizontal DOFs' local
// errors (rtol |u|). Before the floors of the error weights (MultiplierDae::error_scale_floors,
// engaged by the weight function in dae/integrators/ida_integrator.cpp), GGL and index3 collapsed
// to order 1 (order 3 at atol 1e-13) with an error-test failure at every step: at a = 60°, rtol
// 1e-8, atol 1e-10 and t_end 3, GGL took 98,715 steps and ended 1.5e-3 off the circle (at t_end
// 10, 2.5·10⁵ steps, 4e-3 off). docs/schemes.md, "Error weights on rows".
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "dae/formulations/multiplier_dae.hpp"
#include "dae/run/solve.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_trapped_error_test {

namespace {

constexpr double kG = 9.81;

/// Largest distance of the bob from its exact circle over the output rows, in the scene's unit.
double circle_error(const Model& model, const Trajectory& run, double degrees,
                    double length = 1.0) {
  const double a = degrees * std::numbers::pi / 180.0;
  const double r = length * std::sin(a), w = std::sqrt(kG / std::cos(a));
  const int x = model.dof_at("ux2"), y = model.dof_at("uy2"), z = model.dof_at("uz2");
  double worst = 0.0;
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    const double t = run.t[k];
    const auto c = static_cast<Eigen::Index>(k);
    worst = std::max({worst, std::abs(run.u(x, c) - (r * std::cos(w * t) - r)),
                      std::abs(run.u(y, c) - r * std::sin(w * t)), std::abs(run.u(z, c))});
  }
  return worst;
}

}  // namespace

TEST_CASE(
    "steady conical pendulum: GGL and index3 and auto leave the order-1 trap and stay on the "
    "circle") {
  // Bounds: index1 and projection on the same scenes end 6e-8 to 2.5e-6 off the circle in 365
  // to 1,264 steps; GGL and auto must be within 2e-5 (measured 4.5e-8 to 6.8e-6), index3 within
  // 2e-3 (the least accurate scheme per tolerance, docs/schemes.md; measured 2.6e-5 to 1.8e-4).
  // Steps: the trapped runs took 45,496 to 134,911 over these 3 s; now 673 to 1,992.
  for (const double degrees : {45.0, 60.0, 80.0}) {
    CAPTURE(degrees);
    const test::BuiltScene scene =
        test::built(parse_scene_text(test::conical_pendulum_scene(degrees, 3.0), "conical"));
    for (const Scheme scheme : {Scheme::ggl, Scheme::index3, Scheme::automatic}) {
      CAPTURE(std::string(to_string(scheme)));
      const SolveResult run = test::solved(scene.model, test::under(scene.spec.solve, scheme));
      const double err = circle_error(scene.model, run.trajectory, degrees);
      MESSAGE(std::string(to_string(scheme))
              << " at " << degrees << " degrees: " << run.summary.steps << " steps, "
              << run.summary.error_test_failures << " error-test failures, off the circle by "
              << err);
      CHECK(run.summary.steps < 10'000);
      CHECK(err < (scheme == Scheme::index3 ? 2e-3 : 2e-5));
    }
  }
}

TEST_CASE("steady conical pendulum at a tight atol and in millimetres: GGL stays on the circle") {
  // With floors on the displacements only, the velocities' row (GGL's λ) trapped the run at a
  // tighter atol: atol 1e-13 took 70,195 steps over 10 s and ended 2.5e-3 R off, millimetres
  // (atol 1e-10, L = 1000) 111,477 steps and 4.0e-3 R, exit 0 without a warning. Now within 2e-5 R
  // (measured over 10 s: 1.2e-5 and 1.6e-5 R in 3,321 and 3,333 steps; index2 1.3e-6 and 1.7e-6 R).
  struct Case {
    double atol, length;
  };
  for (const Case c : {Case{1e-13, 1.0}, Case{1e-10, 1000.0}}) {
    CAPTURE(c.atol);
    CAPTURE(c.length);
    const test::BuiltScene scene = test::built(parse_scene_text(
        test::conical_pendulum_scene(60.0, 3.0, 1.0, c.atol, c.length), "conical"));
    for (const Scheme scheme : {Scheme::ggl, Scheme::automatic}) {
      CAPTURE(std::string(to_string(scheme)));
      const SolveResult run = test::solved(scene.model, test::under(scene.spec.solve, scheme));
      const double radius = c.length * std::sin(std::numbers::pi / 3.0);
      const double err = circle_error(scene.model, run.trajectory, 60.0, c.length) / radius;
      MESSAGE(std::string(to_string(scheme))
              << " atol " << c.atol << " L " << c.length << ": " << run.summary.steps << " steps, "
              << run.summary.error_test_failures << " error-test failures, off by " << err << " R");
      CHECK(run.summary.steps < 10'000);
      CHECK(err < 2e-5);
    }
  }
}

TEST_CASE("the floors engage only in a trapped run and the summary says when") {
  // The trapped conical pendulum engages them (its note names the time); the same pendulum
  // 10 % faster than steady, a spherical pendulum whose height swings, runs with the plain
  // weights and no note (as do the scenes of models/ and validation/).
  const test::BuiltScene trapped =
      test::built(parse_scene_text(test::conical_pendulum_scene(60.0, 3.0), "conical"));
  const SolveResult ggl = test::solved(trapped.model, test::under(trapped.spec.solve, Scheme::ggl));
  CHECK(ggl.summary.notes_text().find(
            "error weights of the DOFs on constraint rows floored by their rows "
            "from t = ") != std::string::npos);
  const SolveResult index2 =
      test::solved(trapped.model, test::under(trapped.spec.solve, Scheme::index2));
  CHECK(index2.summary.notes_text().find("floored") == std::string::npos);  // no floors to engage
  const test::BuiltScene swinging =  // 10 % faster: an orbit that swings up and down
      test::built(parse_scene_text(test::conical_pendulum_scene(60.0, 3.0, 1.1), "swinging"));
  const SolveResult free_run =
      test::solved(swinging.model, test::under(swinging.spec.solve, Scheme::ggl));
  CHECK(free_run.summary.notes_text().find("floored") == std::string::npos);
}

TEST_CASE("error_scale_floors: each DOF's share of its rows' reach") {
  // Bob at (r, 0, z) on a member from the origin: the member's row is e = (x2 − x1) / L on node
  // 2 and −e on node 1, so |a|² = 2. With u2 = (−0.3, 0.4, 0), the floor of u_z2 is
  // |e_z| (|e_x| 0.3 + |e_y| 0.4) / 2, that of u_x2 |e_x| times the same; node 1's DOFs, in the
  // member's row too, get the same shares (their supports' rows, one DOF each, would floor them
  // at their own |u|, 0).
  const double degrees = 60.0;
  const test::BuiltScene scene =
      test::built(parse_scene_text(test::conical_pendulum_scene(degrees, 1.0), "conical"));
  const MechanicalSystem& system = *scene.model.system;
  for (const Scheme scheme : {Scheme::ggl, Scheme::index3}) {
    CAPTURE(std::string(to_string(scheme)));
    const MultiplierDae dae(system, scheme);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(system.dofs());
    u[scene.model.dof_at("ux2")] = -0.3;
    u[scene.model.dof_at("uy2")] = 0.4;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(system.dofs());
    v[scene.model.dof_at("uy2")] = 2.0;
    const Eigen::VectorXd y = dae.pack(u, v);
    Eigen::VectorXd floor = Eigen::VectorXd::Constant(dae.size(), -1.0);
    REQUIRE(dae.error_scale_floors(0.0, y, floor));
    const double a = degrees * std::numbers::pi / 180.0;
    const double x = std::sin(a) - 0.3, yy = 0.4, z = -std::cos(a);
    const double length = std::sqrt(x * x + yy * yy + z * z);
    const double ax = std::abs(x) / length, ay = yy / length, az = std::abs(z) / length;
    const double reach = (ax * 0.3 + ay * 0.4) / 2.0;
    CHECK(floor[scene.model.dof_at("uz2")] == doctest::Approx(az * reach).epsilon(1e-12));
    CHECK(floor[scene.model.dof_at("ux2")] == doctest::Approx(ax * reach).epsilon(1e-12));
    CHECK(floor[scene.model.dof_at("uy2")] == doctest::Approx(ay * reach).epsilon(1e-12));
    CHECK(floor[scene.model.dof_at("ux1")] == doctest::Approx(ax * reach).epsilon(1e-12));
    CHECK(floor[scene.model.dof_at("uz1")] == doctest::Approx(az * reach).epsilon(1e-12));
    // GGL holds v on every row through λ: the same shares of the velocities' reach, here
    // |e_y| 2 / 2; index3's velocities on rows are out of the error test, no floor.
    const double v_reach = ay * 2.0 / 2.0;
    const Eigen::Index vz2 = system.dofs() + scene.model.dof_at("uz2");
    CHECK(floor[vz2] == doctest::Approx(scheme == Scheme::ggl ? az * v_reach : 0.0).epsilon(1e-12));
    CHECK(floor.tail(dae.size() - 2 * system.dofs()).isZero(0.0));  // λ, μ: none
  }
  for (const Scheme scheme : {Scheme::index1, Scheme::baumgarte, Scheme::index2}) {
    CAPTURE(std::string(to_string(scheme)));
    const MultiplierDae dae(system, scheme);
    Eigen::VectorXd floor = Eigen::VectorXd::Constant(dae.size(), -1.0);
    CHECK_FALSE(dae.error_scale_floors(0.0, Eigen::VectorXd::Zero(dae.size()), floor));
    CHECK(floor.isConstant(-1.0));  // untouched
  }
}

}  // namespace test_trapped_error_test
