// Penalty on nonlinear models, the augmented Lagrangian with iterated multipliers
// (dae/formulations/augmented_lagrangian_ode.hpp): the pendulum and the four-bar against GGL,
// and the IFToMM N-four-bar (A02) through its singular positions, against its closed form.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "dae/run/scheme_choice.hpp"
#include "dae/run/solve.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/nonlinear_runs.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"

using namespace condyn;

namespace test_augmented_lagrangian_validation {

using namespace condyn::test::nonlinear;

namespace {

/// The N-four-bar of validation/references/iftomm/write_A02_scene.py (IFToMM A02) with N windows:
/// N+1 upright cranks of 1 m on the ground pivots (i, 0), N horizontal couplers at y = 1, B0
/// moving at +1 m/s along x; bodies of 1 kg and inertia 1/12.
std::string n_four_bar(int n) {
  std::ostringstream s;
  s << "[model]\ntype = \"multibody\"\ndimension = 2\ngravity = [0.0, -9.81]\nground = { ";
  for (int i = 0; i <= n; ++i) s << (i ? ", " : "") << "A" << i << " = [" << i << ".0, 0.0]";
  s << " }\n";
  for (int i = 0; i <= n; ++i) {
    s << "[[body]]\nname = \"crank" << i << "\"\nmass = 1.0\ninertia = 0.08333333333333333\n"
      << "position = [" << i << ".0, 0.5]\nangle = 1.5707963267948966\nvelocity = [0.5, 0.0]\n"
      << "angular_velocity = -1.0\npoints = { A = [-0.5, 0.0], B = [0.5, 0.0] }\n";
  }
  for (int i = 1; i <= n; ++i) {
    s << "[[body]]\nname = \"coupler" << i << "\"\nmass = 1.0\ninertia = 0.08333333333333333\n"
      << "position = [" << i - 0.5 << ", 1.0]\nangle = 0.0\nvelocity = [1.0, 0.0]\n"
      << "points = { L = [-0.5, 0.0], R = [0.5, 0.0] }\n";
  }
  const auto joint = [&](const std::string& name, const std::string& a, const std::string& b,
                         const char* pa, const char* pb) {
    s << "[[joint]]\nname = \"" << name << "\"\ntype = \"revolute\"\nbodies = [\"" << a << "\", \""
      << b << "\"]\npoints = [\"" << pa << "\", \"" << pb << "\"]\n";
  };
  for (int i = 0; i <= n; ++i)
    joint("A" + std::to_string(i), "ground", "crank" + std::to_string(i),
          ("A" + std::to_string(i)).c_str(), "A");
  for (int i = 1; i <= n; ++i) {
    const std::string c = "coupler" + std::to_string(i);
    joint("B" + std::to_string(i - 1) + "_L", "crank" + std::to_string(i - 1), c, "B", "L");
    joint("B" + std::to_string(i) + "_R", "crank" + std::to_string(i), c, "B", "R");
  }
  s << "[solve]\nt_end = 5.0\noutput_step = 0.05\n";  // the test sets its own
  return s.str();
}

/// The crank angle φ(t) and φ'(t) on the parallelogram branch (validation/references/iftomm/
/// reference_A02.py): m_eff φ'' = −V cos φ, m_eff = (N+1)/3 + N, V = ((N+1)/2 + N) g (unit
/// masses and lengths), φ(0) = π/2, φ'(0) = −1. Classical Runge-Kutta at h = 1e-4: its error,
/// h⁴ times φ's fifth derivative (of order (V/m_eff)^{5/2} ≈ 1e3) per unit time, is below 1e-12.
struct Branch {
  double phi, rate;
};
Branch branch_at(int n, double t) {
  const double m_eff = (n + 1) / 3.0 + n, v = ((n + 1) / 2.0 + n) * 9.81;
  const auto f = [&](const Branch& y) { return Branch{y.rate, -v * std::cos(y.phi) / m_eff}; };
  Branch y{std::numbers::pi / 2.0, -1.0};
  const int steps = static_cast<int>(std::ceil(t / 1e-4));
  const double h = steps > 0 ? t / steps : 0.0;
  for (int k = 0; k < steps; ++k) {
    const Branch k1 = f(y), k2 = f({y.phi + h / 2 * k1.phi, y.rate + h / 2 * k1.rate}),
                 k3 = f({y.phi + h / 2 * k2.phi, y.rate + h / 2 * k2.rate}),
                 k4 = f({y.phi + h * k3.phi, y.rate + h * k3.rate});
    y.phi += h / 6 * (k1.phi + 2 * k2.phi + 2 * k3.phi + k4.phi);
    y.rate += h / 6 * (k1.rate + 2 * k2.rate + 2 * k3.rate + k4.rate);
  }
  return y;
}

}  // namespace

TEST_CASE("penalty on nonlinear scenes is the augmented Lagrangian and agrees with GGL") {
  // Over 2 s at rtol 1e-10 (atol 1e-12) against GGL at rtol 1e-12 (atol 1e-14), the bounds of
  // the other schemes on these scenes (tests/dae/test_partitioned_elimination_validation.cpp): 2e4
  // × rtol in u, v and the reactions (O(1) lengths, speeds and forces). Observed: see the MESSAGE
  // lines.
  for (const char* name : {"pendulum.toml", "four_bar.toml"}) {
    CAPTURE(std::string(name));
    const test::BuiltScene built = scene(name, 2.0, kRtol);
    const Model& model = built.model;
    REQUIRE(model.is_nonlinear());
    REQUIRE_FALSE(scheme_refusal(model, Scheme::penalty).has_value());
    const SolveSpec tight = tight_ggl(built.spec.solve);
    const Trajectory ref = test::solved(model, tight).trajectory;
    const SolveResult result = test::solved(model, test::under(built.spec.solve, Scheme::penalty));
    CHECK(result.scheme == Scheme::penalty);
    const TrajectoryError err = relative_error(result.trajectory, ref);
    MESSAGE(std::string(name) << ": err u " << err.displacement << ", v " << err.velocity
                              << ", reaction " << err.reaction << "; "
                              << result.summary.notes_text());
    CHECK(err.displacement < 2e4 * kRtol);
    CHECK(err.velocity < 2e4 * kRtol);
    CHECK(err.reaction < 2e4 * kRtol);
  }
}

TEST_CASE("penalty passes the N-four-bar's singular positions on the parallelogram branch") {
  // IFToMM A02 with N = 1 and N = 4 windows over 5 s: φ passes 0 or π (every link on the ground
  // line, A loses rank and N more DOF appear) about once a second. Every crank must turn with
  // φ(t) of the closed form and every coupler stay horizontal (uy = 0).
  constexpr double kRtol = 1e-8, kEnd = 5.0;
  // The IFToMM specification's "high precision" bound on A02's positions, 1e-3 m (the header of
  // models/scenes/iftomm/A02_n_four_bar.toml): each passage goes through the regularization the
  // iteration cap leaves (augmented_lagrangian_ode.hpp), which costs some phase. Leaving the
  // branch is an O(1) error. Observed: see the MESSAGE lines.
  constexpr double kTolerance = 1e-3;
  for (int n : {1, 4}) {
    CAPTURE(n);
    SceneSpec spec = parse_scene_text(n_four_bar(n), "A02 N = " + std::to_string(n));
    spec.solve.t_end = kEnd;
    spec.solve.output_step = 0.05;
    spec.solve.rtol = kRtol;
    spec.solve.atol = kRtol * 1e-2;
    spec.solve.scheme = Scheme::penalty;
    const test::BuiltScene built = test::built(spec);
    const Model& model = built.model;
    const SolveResult result = test::solved(model, spec.solve);
    const Trajectory& run = result.trajectory;
    const auto dof = [&](const std::string& name) {
      const auto at = std::find(model.dof_names.begin(), model.dof_names.end(), name);
      REQUIRE(at != model.dof_names.end());
      return static_cast<Eigen::Index>(at - model.dof_names.begin());
    };
    double worst = 0.0;
    int passages = 0;
    double last_sin = 1.0;
    for (std::size_t k = 0; k < run.t.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      const Branch b = branch_at(n, run.t[k]);
      const double c = std::cos(b.phi), s = std::sin(b.phi);
      if (s * last_sin < 0.0) ++passages;
      last_sin = s;
      for (int i = 0; i <= n; ++i) {
        const std::string crank = "crank" + std::to_string(i);
        worst = std::max({worst, std::abs(run.u(dof(crank + ".ux"), col) - c),
                          std::abs(run.u(dof(crank + ".uy"), col) - s)});
      }
      for (int i = 1; i <= n; ++i) {
        worst = std::max(worst, std::abs(run.u(dof("coupler" + std::to_string(i) + ".uy"), col)));
      }
    }
    MESSAGE("N = " << n << ": " << passages << " singular passages, largest error " << worst << "; "
                   << result.summary.notes_text());
    CHECK(passages >= 4);
    CHECK(worst < kTolerance);
  }
}

}  // namespace test_augmented_lagrangian_validation
