// The Newmark family stabilized at index 2 ([solve] newmark_constraints = "stabilized";
// dae/integrators/stabilized_newmark_newton.hpp): its Newton matrix against central differences
// of its residual along its own increments, the velocity constraints held to Newton's tolerance
// where index 3 leaves a drift of order h², λ meaning what it means under the other schemes, the
// key's default and its refusals, and `info`'s sizes against the run's.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "dae/integrators/stabilized_newmark_newton.hpp"
#include "dae/run/scheme_choice.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/compare.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_newmark_stabilized {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// models/scenes/pendulum.toml (a unit mass on a rigid member of 1 m under gravity) with
/// `solve_keys` added to [solve].
std::string pendulum(const std::string& solve_keys) {
  return test::pendulum_scene("t_end = 1.0\noutput_step = 0.1\nscheme = \"generalized_alpha\"\n" +
                              solve_keys);
}

test::BuiltScene scene_file(const std::string& name) {
  return test::built(
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/" + name + ".toml"));
}

/// The residual after applying the increment d from the predictor `base` with a fresh Newton
/// system (its Newmark displacement starts at the predictor's u, as at a step's start).
Eigen::VectorXd residual_after(MechanicalSystem& system, bool linear, const StepState& base,
                               const StepCoefficients& c, double t, const Eigen::VectorXd& d) {
  StabilizedNewmarkNewton newton(system, linear);
  StepState x = base;
  newton.begin_step(x);
  newton.apply(t, d, c, x);
  Eigen::VectorXd r;
  newton.residual(t, x, c, r);
  return r;
}

}  // namespace

TEST_CASE("stabilized newmark: the Newton matrix is the derivative of the residual") {
  // Column j of the matrix at the state reached by the increment d0 against central differences
  // of the residual along d0 ± δ e_j (δ = 1e-6, the states O(1)): their error is O(δ²) times
  // the third derivatives, O(1) here, plus roundoff eps |r| / δ; 1e-7 of the matrix's largest
  // entry bounds both (observed 6e-12 to 3e-11 against entries up to 2.1).
  constexpr double kDelta = 1e-6, kFdTolerance = 1e-7;
  // pendulum: a nonlinear position row (H = ∂(A_pᵀμ)/∂u nonzero); double pendulum: two;
  // chain_driven_base: linear, damped, a driven row and a velocity-level row (the D_v blocks).
  for (const std::string name : {"pendulum", "double_pendulum", "chain_driven_base"}) {
    CAPTURE(name);
    const auto scene = scene_file(name);
    const auto system = scene.model.system->clone();
    const bool linear = !scene.model.nonlinear;
    const int n = system->dofs(), m = system->constraints();
    StabilizedNewmarkNewton probe(*system, linear);
    const int size = n + m + probe.mu_size();
    REQUIRE(probe.mu_size() > 0);
    // A state off the solution (so that every term of the matrix counts): the model's start
    // moved by a fixed pattern, velocities and accelerations O(1), λ O(10).
    const Eigen::VectorXd pattern = Eigen::VectorXd::LinSpaced(n, 0.3, -0.7);
    StepState base{scene.model.u0 + 0.05 * pattern, scene.model.v0 + pattern, pattern.reverse(),
                   Eigen::VectorXd::LinSpaced(m, 7.0, -4.0), Eigen::VectorXd()};
    const StepCoefficients c{1.3e3, 57.0};
    const double t = 0.37;
    const Eigen::VectorXd d0 = 0.01 * Eigen::VectorXd::LinSpaced(size, 1.0, -2.0);
    StabilizedNewmarkNewton newton(*system, linear);
    StepState x = base;
    newton.begin_step(x);
    newton.apply(t, d0, c, x);
    const Eigen::MatrixXd J = Eigen::MatrixXd(newton.matrix(t, x, c));
    Eigen::MatrixXd fd(size, size);
    for (int j = 0; j < size; ++j) {
      Eigen::VectorXd plus = d0, minus = d0;
      plus[j] += kDelta;
      minus[j] -= kDelta;
      fd.col(j) = (residual_after(*system, linear, base, c, t, plus) -
                   residual_after(*system, linear, base, c, t, minus)) /
                  (2.0 * kDelta);
    }
    MESSAGE(name << ": largest difference " << (J - fd).cwiseAbs().maxCoeff() << " of "
                 << fd.cwiseAbs().maxCoeff());
    CONDYN_CHECK_CLOSE(J, fd, kFdTolerance);
  }
}

TEST_CASE("stabilized newmark holds the velocity constraints where index 3 drifts as h^2") {
  // The pendulum's rod: under the stabilized form ψ = A v holds at every step to what Newton's
  // tolerance on u leaves of it, γ' (rtol |u| + atol) (a residual δu in u is one of γ' δu in v
  // through Δv = γ' Δw), 2e-8 at h = 0.01 (observed: roundoff, under 1e-14); at index 3 the
  // velocity constraint is not among the equations, and its drift shrinks as h² (observed 6.8e-4
  // and 1.7e-4 at h = 0.01 and 0.005: a ratio of 4.0; asserted in [3, 5], order 2 within ±0.3).
  // The position drift of both is Newton's tolerance, rtol |u| + atol.
  constexpr double kRtol = 1e-10, kAtol = 1e-12, kRodLength = 1.0;
  constexpr double kMinRatio = 3.0, kMaxRatio = 5.0;
  const AlphaParameters p = generalized_alpha_parameters(kDefaultRhoInf);
  const std::string tolerances = "rtol = 1e-10\natol = 1e-12\n";
  std::vector<double> index3_drift;
  for (const double h : {0.01, 0.005}) {
    CAPTURE(h);
    const double gamma_prime = p.gamma / (h * p.beta);
    const double position_tolerance = kRtol * kRodLength + kAtol;
    const std::string step = "step = " + std::to_string(h) + "\n";
    const auto stabilized = test::built(parse_scene_text(
        pendulum(step + tolerances + "newmark_constraints = \"stabilized\"\n"), "p.toml"));
    const auto index3 = test::built(parse_scene_text(pendulum(step + tolerances), "p.toml"));
    const SolveSummary s = test::solved(stabilized.model, stabilized.spec.solve).summary;
    const SolveSummary i = test::solved(index3.model, index3.spec.solve).summary;
    MESSAGE("h = " << h << ": velocity drift " << s.max_drift_velocity << " stabilized, "
                   << i.max_drift_velocity << " index 3; position drift " << s.max_drift_position
                   << ", " << i.max_drift_position << "; max |mu| " << s.max_abs_mu);
    CHECK(s.max_drift_velocity <= gamma_prime * position_tolerance);
    CHECK(s.max_drift_position <= position_tolerance);
    CHECK(i.max_drift_position <= position_tolerance);
    CHECK(i.max_drift_velocity > 1e3 * gamma_prime * position_tolerance);
    CHECK(s.max_abs_mu >= 0.0);  // μ observed and summarized, as GGL's
    index3_drift.push_back(i.max_drift_velocity);
  }
  const double ratio = index3_drift[0] / index3_drift[1];
  CHECK(ratio >= kMinRatio);
  CHECK(ratio <= kMaxRatio);
}

TEST_CASE("stabilized newmark on a linear model: one factorization per step size, as index 3") {
  // chain_driven_base: position rows (one driven), a velocity-level row and damping. Its matrix
  // depends on the step alone, so the stabilized run factors it as often as the index-3 run
  // does; its velocity drift is at roundoff of the velocities (eps times 1e3 times their size,
  // the step's γ' = 1/(hβ) amplifying roundoff in u) where index 3's is O(h²).
  auto scene = scene_file("chain_driven_base");
  scene.spec.solve.step = 0.01;
  scene.spec.solve.scheme = Scheme::newmark;
  const SolveResult index3 = test::solved(scene.model, scene.spec.solve);
  scene.spec.solve.newmark_family.constraints = NewmarkConstraints::stabilized;
  const SolveResult stabilized = test::solved(scene.model, scene.spec.solve);
  CHECK(stabilized.summary.jacobian_evals == index3.summary.jacobian_evals);
  const double velocity_scale = stabilized.trajectory.v.cwiseAbs().maxCoeff();
  constexpr double kRoundoffFactor = 1e3;
  MESSAGE("velocity drift " << stabilized.summary.max_drift_velocity << " stabilized, "
                            << index3.summary.max_drift_velocity << " index 3 (scale "
                            << velocity_scale << ")");
  CHECK(stabilized.summary.max_drift_velocity <= kRoundoffFactor * kEps * velocity_scale);
  CHECK(index3.summary.max_drift_velocity > kRoundoffFactor * kEps * velocity_scale);
}

TEST_CASE("newmark_constraints: index3 by default, stabilized on request, others refused") {
  const auto plain = parse_scene_text(pendulum("step = 0.01\n"), "p.toml");
  CHECK(plain.solve.newmark_family.constraints == NewmarkConstraints::index3);
  const auto named =
      parse_scene_text(pendulum("step = 0.01\nnewmark_constraints = \"stabilized\"\n"), "p.toml");
  CHECK(named.solve.newmark_family.constraints == NewmarkConstraints::stabilized);
  test::check_parse_error(pendulum("step = 0.01\nnewmark_constraints = \"index2\"\n"),
                          "bad.toml:13: solve.newmark_constraints: expected 'index3'");
  test::check_parse_error(pendulum("step = 0.01\nnewmark_constraints = 2\n"),
                          "solve.newmark_constraints");
}

TEST_CASE("info's size of the stabilized form is the run's") {
  // [u; v; λ; μ] (2n + m + m_p) and the stabilized matrix's stored entries, at t = 0 as at
  // every state (its pattern fixed).
  for (const std::string name : {"double_pendulum", "chain_driven_base"}) {
    CAPTURE(name);
    auto scene = scene_file(name);
    scene.spec.solve.scheme = Scheme::generalized_alpha;
    scene.spec.solve.step = 0.01;
    scene.spec.solve.t_end = 0.1;
    scene.spec.solve.output_step = 0.1;
    scene.spec.solve.newmark_family.constraints = NewmarkConstraints::stabilized;
    const SystemSize size = system_size(scene.model, scene.spec.solve);
    const SolveSummary s = test::solved(scene.model, scene.spec.solve).summary;
    CHECK(size.unknowns == s.unknowns);
    CHECK(size.jacobian_nonzeros == s.jacobian_nonzeros);
    CHECK(size.unknowns > 2 * scene.model.dofs() + scene.model.constraint_count());
  }
}

}  // namespace test_newmark_stabilized
