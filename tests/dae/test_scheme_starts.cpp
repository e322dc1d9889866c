// Issue 10, items 3 and 7: index3 starts from any configuration, Baumgarte gains from the model's
// own time scales (item 4, index1 at a tight tolerance, is in test_scheme_starts_validation.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "dae/formulations/baumgarte_gains.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"

using namespace condyn;

namespace test_scheme_starts {

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();

constexpr double kG = 9.81;

/// A pendulum: support at the origin, a unit mass at `mass_at` (2 or 3 coordinates), released
/// from rest under gravity along −y (2D) or −z (3D).
std::string pendulum(const std::vector<double>& mass_at, const std::string& solve_extra,
                     double output_step = 0.01) {
  const bool three_d = mass_at.size() == 3;
  std::ostringstream s;
  s.precision(17);
  s << "[model]\ntype = \"" << (three_d ? "truss3d" : "truss2d") << "\"\nnodes = [["
    << (three_d ? "0.0, 0.0, 0.0" : "0.0, 0.0") << "], [";
  for (std::size_t i = 0; i < mass_at.size(); ++i) s << (i ? ", " : "") << mass_at[i];
  s << "]]\nmasses = [0.0, 1.0]\nsupports = [1]\nmembers = [{ nodes = [1, 2], rigid = true }]\n"
    << "gravity = " << (three_d ? "[0.0, 0.0, -9.81]" : "[0.0, -9.81]") << "\n"
    << "[solve]\nt_end = 1.0\noutput_step = " << output_step << "\nrtol = 1e-8\n"
    << solve_extra;
  return s.str();
}

test::BuiltScene scene_file(const std::string& name, double t_end, double rtol) {
  SceneSpec spec = test::shipped_scene(name);
  spec.solve.t_end = t_end;
  spec.solve.rtol = rtol;
  return test::built(spec);
}

/// The Baumgarte gains of a scene under its own settings.
BaumgarteGains gains_of(const std::string& text) {
  const SceneSpec spec = parse_scene_text(text, "pendulum");
  return baumgarte_gains(build_model(spec), spec.solve);
}

}  // namespace

TEST_CASE("index3 starts a pendulum released from rest at any angle, length and dimension") {
  // The rod oblique at [0.6, -0.8] failed at t = 0: the first step was 1e-8 of the output step
  // (1e-10 s), where index3's Newton matrix (condition ~ 1/h²) is singular in double precision
  // (IDA_LSETUP_FAIL with KLU, IDA_CONV_FAIL with the dense solver). Horizontal and vertical rods
  // have one nonzero per constraint row and escaped. Each run is compared with GGL at the same
  // rtol 1e-8: index3 leaves v out of the error test and is the least accurate scheme per
  // tolerance (tests/validation/test_nonlinear_validation.cpp: up to 3.6e-5 at rtol 1e-10 on the
  // four-bar), so 1e4 × rtol relative in u, ten times the common kGlobalErrorFactor (observed up
  // to 1.7e-5, 1.7e3 × rtol): the same motion, not a bare start.
  const std::vector<std::vector<double>> positions = {
      {0.6, -0.8}, {-0.28, 0.96}, {0.3, -0.4},        {6.0, -8.0},
      {0.5, -0.5}, {0.8, 0.6},    {0.48, -0.64, 0.6}, {-0.36, 0.48, -0.8}};
  for (const auto& at : positions) {
    for (const char* solver : {"klu", "dense"}) {
      std::ostringstream where;
      for (double x : at) where << x << " ";
      CAPTURE(where.str());
      CAPTURE(std::string(solver));
      const SceneSpec spec = parse_scene_text(
          pendulum(at, std::string("linear_solver = \"") + solver + "\"\n"), "pendulum");
      const Model model = build_model(spec);
      const SolveResult run = solve(model, test::under(spec.solve, Scheme::index3));
      const SolveResult ref = solve(model, test::under(spec.solve, Scheme::ggl));
      REQUIRE(run.ok());
      REQUIRE(ref.ok());
      CHECK(relative_error(run.trajectory, ref.trajectory).displacement < 1e4 * 1e-8);
    }
  }
}

TEST_CASE("Baumgarte's default gains come from the model, not from output_step") {
  // A pendulum has no elastic stiffness: its time scale is the gravity stiffness m g / L of the
  // rod force (dae/formulations/model_scales.hpp), so β = α = √(g/L) — before, 2π / output_step.
  for (const double length : {1.0, 2.5}) {
    CAPTURE(length);
    const BaumgarteGains a = gains_of(pendulum({length, 0.0}, "", 0.001));
    const BaumgarteGains b = gains_of(pendulum({length, 0.0}, "", 0.1));
    CHECK(a.beta == b.beta);
    CHECK(a.alpha == b.alpha);
    // Eigenvalues of a 1 x 1 reduced problem: exact to a few eps (observed exact).
    CHECK(a.beta == doctest::Approx(std::sqrt(kG / length)).epsilon(8 * kEps));
    CHECK(a.alpha == a.beta);
  }
  // Oblique and moving: the rod force at t = 0 (m g cos θ + m v²/L) or the gravity scale,
  // whichever is larger; output_step still plays no part.
  const BaumgarteGains fine = gains_of(pendulum({0.6, -0.8}, "", 0.001));
  const BaumgarteGains coarse = gains_of(pendulum({0.6, -0.8}, "", 0.2));
  CHECK(fine.beta == coarse.beta);
  CHECK(fine.beta >= std::sqrt(kG) * (1.0 - 8 * kEps));
}

TEST_CASE("GGL and index3 start where a drive's own roundoff exceeds atol") {
  // 1e6 sin(t + π) is 1.2e-10 at t = 0 (sin π is not 0 in doubles), beside u(0) = 0: accepted
  // as consistent (roundoff of the data), but GGL and index3 hold the row to atol = 1e-12 from
  // their first step and failed the error test at t = 0 until u0 was settled onto the row.
  const std::string text = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
[[constraint]]
name = "drive"
terms = { a = 1.0 }
value = { type = "harmonic", amplitude = 1e6, omega = 1.0, phase = 3.141592653589793 }
[initial]
velocity = { a = -1e6 }
[solve]
t_end = 1.0
output_step = 0.5
rtol = 1e-8
atol = 1e-12
constraints = "multipliers"
)";
  const SceneSpec spec = parse_scene_text(text, "drive.toml");
  const Model model = build_model(spec);
  CHECK(model.u0[0] == 1e6 * std::sin(3.141592653589793));  // settled exactly onto the row
  for (const Scheme scheme : {Scheme::ggl, Scheme::index3, Scheme::index1}) {
    CAPTURE(to_string(scheme));
    const SolveResult r = solve(model, test::under(spec.solve, scheme));
    CHECK(r.ok());
  }
}

TEST_CASE("GGL starts the stiff flyball governor (IFToMM A05) at its scene's atol 1e-12") {
  // Its fastest mode (ω_max = 404 rad/s, the spring-dampers) takes steps of about 1e-3 s, over
  // which the BDF derivative u' carries u's roundoff, eps |u| / h ~ 1e-13 for its 1 m bodies:
  // the velocity and μ atols derived from atol alone (1e-13) lay below it, and GGL failed before
  // its first step (IDA_CONV_FAIL at t = 0, h = 5.9e-15).
  const test::BuiltScene scene = scene_file("iftomm/A05_flyball_governor.toml", 0.05, 1e-10);
  REQUIRE(scene.spec.solve.atol == 1e-12);
  const SolveResult r = solve(scene.model, test::under(scene.spec.solve, Scheme::ggl));
  CHECK(r.ok());
}

}  // namespace test_scheme_starts
