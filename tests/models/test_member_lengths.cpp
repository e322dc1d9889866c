// Members near the ends of the double range. A rigid member's residual was (|d|² − L²)/(2L): from
// |d| ~ 1e154 the squares overflow, so a pendulum of length 1e200 was refused with "residual
// -nan" (issue 42); a large-displacement bar's length |d| overflowed the same way (its force
// NaN), and below 1e-154 the squares underflow. Lengths and residuals are now computed on values
// scaled by a power of 2 (models/systems/point_mass_system.cpp): every length from 1e-80 to 1e300
// runs as the unit one does, and a residual that does overflow is named so in the message, never
// "nan".
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_member_lengths {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// The lengths tried: tiny (squares below the smallest double), 1, and large (squares beyond the
/// largest) up to near the top of the range.
constexpr double kLengths[] = {1e-160, 1e-100, 1e-80, 1.0, 1e154, 1e200, 1e300};

/// A pendulum of length `length` (a rigid member from the support, node 1, to a unit mass,
/// node 2) released horizontally from rest over half its period T = 4 √(L/g) K(1/√2)
/// (K(1/√2) = 1.8540746773013719), at rtol 1e-8 and atol 1e-10 L: in units of L and √(L/g) the
/// same problem at every L. `atol_floor`: the least atol written (the parser refuses one below
/// 1e-100), for the cases that only build the model.
std::string pendulum(double length, double atol_floor = 0.0) {
  const double period = 4.0 * std::sqrt(length / 9.81) * 1.8540746773013719;
  std::ostringstream s;
  s.precision(17);
  s << "[model]\ntype = \"truss2d\"\nnodes = [[0.0, 0.0], [" << length
    << ", 0.0]]\nmasses = [0.0, 1.0]\nsupports = [1]\n"
       "members = [{ nodes = [1, 2], rigid = true }]\ngravity = [0.0, -9.81]\n"
       "[solve]\nscheme = \"ggl\"\nt_end = "
    << period / 2.0 << "\noutput_step = " << period / 10.0
    << "\nrtol = 1e-8\natol = " << std::max(1e-10 * length, atol_floor) << "\n";
  return s.str();
}

/// The least atol the parser takes (kMinAtol, models/scene/read_solve.cpp).
constexpr double kLeastAtol = 1e-100;

/// A bar of length `length` with large-displacement geometry between a support and a unit mass.
std::string bar(double length) {
  std::ostringstream s;
  s.precision(17);
  s << "[model]\ntype = \"truss2d\"\ngeometry = \"nonlinear\"\nnodes = [[0.0, 0.0], [" << length
    << ", 0.0]]\nmasses = [0.0, 1.0]\nsupports = [1]\n"
       "members = [{ nodes = [1, 2], EA = 1.0 }]\n"
       "[solve]\nt_end = 1.0\noutput_step = 0.5\n";
  return s.str();
}

}  // namespace

TEST_CASE("member lengths: a rigid member's residuals at lengths from 1e-160 to 1e300") {
  // Node 2 (DOFs 2, 3) moved by (L/2, 0): |d| = 1.5 L, φ = (2.25 − 1) L / 2 = 0.625 L; moving at
  // (0, L): γ = −|v|²/L = −L. Each to a few roundings of the lengths: 8 eps relative.
  for (const double length : kLengths) {
    CAPTURE(length);
    const Model model =
        build_model(parse_scene_text(pendulum(length, kLeastAtol), "pendulum.toml"));
    const auto system = model.evaluator();
    const int rod = system->constraints() - 1;  // after the support's rows
    Eigen::VectorXd u = Eigen::VectorXd::Zero(4), v = Eigen::VectorXd::Zero(4);
    Eigen::VectorXd phi(system->constraints()), gamma(system->constraints());
    system->position_residual(0.0, u, phi);
    CHECK(phi[rod] == 0.0);  // at the reference geometry: exactly
    u[2] = 0.5 * length;
    v[3] = length;
    system->position_residual(0.0, u, phi);
    system->acceleration_bias(0.0, u, v, gamma);
    CHECK(std::abs(phi[rod] / length - 0.625) <= 8 * kEps);
    CHECK(std::abs(gamma[rod] / length + 1.0) <= 8 * kEps);
  }
}

TEST_CASE("member lengths: a large-displacement bar's force at lengths from 1e-160 to 1e300") {
  // Stretched by L/2: N = EA (l − L)/L = 0.5 EA, pulling node 2 back (f = −0.5 on ux2), to a
  // few roundings of the lengths (8 eps); its strain energy EA (l − L)²/(2L) = L/8.
  for (const double length : kLengths) {
    CAPTURE(length);
    const Model model = build_model(parse_scene_text(bar(length), "bar.toml"));
    const auto system = model.evaluator();
    Eigen::VectorXd u = Eigen::VectorXd::Zero(4), f(4);
    const Eigen::VectorXd v = Eigen::VectorXd::Zero(4);
    u[2] = 0.5 * length;
    system->force(0.0, u, v, f);
    CHECK(std::abs(f[2] + 0.5) <= 8 * kEps);
    CHECK(f[3] == 0.0);
    const auto parts = system->energy_parts(0.0, u, v);
    REQUIRE(parts.has_value());
    CHECK(std::abs(parts->potential / length - 0.125) <= 8 * kEps);
  }
}

TEST_CASE("member lengths: pendulums of length 1e-160 to 1e300 swing as the unit pendulum") {
  // In units of L and √(L/g) every run is the same problem under the same tolerances, so the
  // swing at half a period, u/L, agrees with the unit pendulum's to the runs' own errors: within
  // 100 rtol (each run's global error is ~10 rtol: measured 6e-11 to 1.7e-7 off, drift 4e-9 L to
  // 2.3e-8 L, from L = 1e-80 to 1e300; the steps differ, 272 to 350). Below L = 1e-90 the
  // scaled atol (1e-10 L) is one the parser refuses, by name: no scaled run can be asked for.
  const auto run = [](double length) {
    const test::BuiltScene scene = test::built(parse_scene_text(pendulum(length), "pendulum"));
    return test::solved(scene.model, scene.spec.solve);
  };
  const SolveResult unit = run(1.0);
  const Eigen::Index last = unit.trajectory.u.cols() - 1;
  for (const double length : kLengths) {
    CAPTURE(length);
    if (1e-10 * length < kLeastAtol) {
      CHECK_THROWS_WITH_AS(run(length), doctest::Contains("solve.atol: is too small"), SceneError);
      continue;
    }
    const SolveResult r = run(length);
    REQUIRE(r.trajectory.u.cols() == last + 1);
    const double off =
        (r.trajectory.u.col(last) / length - unit.trajectory.u.col(last)).cwiseAbs().maxCoeff();
    MESSAGE("L = " << length << ": " << r.summary.steps << " steps, u/L off the unit pendulum's by "
                   << off << ", drift " << r.summary.max_drift_position / length << " L");
    CHECK(off <= 100 * 1e-8);
    CHECK(r.summary.max_drift_position <= 100 * 1e-8 * length);
  }
}

TEST_CASE("member lengths: a residual that overflows is named, never printed as nan") {
  // Node 2 moved 1e300 off a member of length 1: φ ≈ |d|²/(2L) = 5e599, beyond the double range
  // (its Jacobian d/L = 1e300 is not), a start that violates the member. The message says so
  // instead of "residual inf" or "-nan".
  const std::string scene =
      "[model]\ntype = \"truss2d\"\nnodes = [[0.0, 0.0], [1.0, 0.0]]\nmasses = [0.0, 1.0]\n"
      "supports = [1]\nmembers = [{ nodes = [1, 2], rigid = true }]\n"
      "[initial]\ndisplacement = { ux2 = 1e300 }\n"
      "[solve]\nt_end = 1.0\noutput_step = 0.5\n";
  std::string message;
  try {
    (void)build_model(parse_scene_text(scene, "far.toml"));
  } catch (const SceneError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK(message.find("initial displacements violate constraint 'rigid_1_2'") != std::string::npos);
  CHECK(message.find("residual infinite (products of the initial coordinates, lengths and "
                     "velocities overflow the double range)") != std::string::npos);
  CHECK(message.find("nan") == std::string::npos);
  CHECK(message.find("inf;") == std::string::npos);
}

}  // namespace test_member_lengths
