// Elimination of nonlinear models by coordinate partitioning
// (dae/formulations/partitioned_ode.hpp): the partition's quality against a dense solve, the
// reactions from the full equations, a failure at a singular position of the mechanism as data,
// the refusal of nonholonomic rows, GMRES on a long chain, a fully driven mechanism. The long
// runs against GGL (the pendulum, the four-bar, its re-partitions, Andrews' mechanism) and GMRES
// against the dense Jacobian are validation-tier cases:
// test_partitioned_elimination_validation.cpp.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <Eigen/Dense>

#include "dae/formulations/coordinate_partition.hpp"
#include "dae/formulations/partitioned_ode.hpp"
#include "dae/run/scheme_choice.hpp"
#include "dae/run/solve.hpp"
#include "models/core/constraint_drift.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/singular_values.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/nonlinear_runs.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"

using namespace condyn;

namespace test_partitioned_elimination {

using namespace condyn::test::nonlinear;

TEST_CASE("coordinate partitioning: the reactions are the full equations' λ") {
  // The pendulum's unit mass on its horizontal rod of length 1, moving at 2 m/s across it: M u''
  // = f − Aᵀλ with u'' from the same KKT solve, and A u'' = γ, with residuals at roundoff of the
  // forces (64 eps × 10 N); the rod pulls the mass toward the pivot with m v²/L = 4 N (gravity,
  // across the rod, adds nothing to it).
  const test::BuiltScene built = scene("pendulum.toml", 1.0, kRtol);
  const Model& model = built.model;
  PartitionedOde ode(model, 0.0);
  ode.set_newton_tolerance(1e-3 * kRtol * 1e-2);
  auto system = model.evaluator();
  REQUIRE(ode.partition().independent == std::vector<int>{*model.find_dof("uy2")});
  Eigen::VectorXd y0 = ode.initial_state();
  y0[1] = -2.0;  // [uy2; its velocity]
  const PartitionedOde::Full f = ode.full(0.0, y0);
  Eigen::VectorXd force(model.dofs()), gamma(model.constraint_count());
  system->force(0.0, f.u, f.v, force);
  system->acceleration_bias(0.0, f.u, f.v, gamma);
  const auto& A = system->constraint_jacobian(0.0, f.u);
  const Eigen::VectorXd momentum =
      system->mass(0.0, f.u) * f.a - force + Eigen::VectorXd(A.transpose() * f.lambda);
  constexpr double kRoundoff = 64 * std::numeric_limits<double>::epsilon() * 10.0;
  CHECK(momentum.lpNorm<Eigen::Infinity>() <= kRoundoff);
  CHECK((A * f.a - gamma).lpNorm<Eigen::Infinity>() <= kRoundoff);
  const Eigen::VectorXd reaction = -(A.transpose() * f.lambda);
  CHECK(reaction[*model.find_dof("ux2")] == doctest::Approx(-4.0).epsilon(kRoundoff));
  CHECK(std::abs(reaction[*model.find_dof("uy2")]) <= kRoundoff);
}

TEST_CASE("elimination refuses nonholonomic rows only, saying why") {
  const test::BuiltScene sleigh = scene("chaplygin_sleigh.toml", 1.0, 1e-8);
  const auto why = scheme_refusal(sleigh.model, Scheme::elimination);
  REQUIRE(why);
  CHECK(why->find("elimination cannot treat a nonholonomic constraint") == 0);
  CHECK(why->find("coordinate partitioning") != std::string::npos);
  CHECK_THROWS_AS((void)PartitionedOde(sleigh.model, 0.0), SchemeNotApplicable);
  // Nonlinear holonomic scenes are not refused, and auto still picks GGL for them, saying why.
  const test::BuiltScene pendulum = scene("pendulum.toml", 1.0, 1e-8);
  CHECK_FALSE(scheme_refusal(pendulum.model, Scheme::elimination).has_value());
  const SchemeChoice choice =
      choose_scheme(pendulum.model, test::under(pendulum.spec.solve, Scheme::automatic));
  CHECK(choice.scheme == Scheme::ggl);
  CHECK(choice.reason.find("coordinate partitioning") != std::string::npos);
}

TEST_CASE(
    "coordinate partitioning through a singular position of the mechanism: a failure as data") {
  // parallelogram_four_bar.toml puts every link on the ground line at t = 1: no partition has a
  // regular dependent block there, the Newton iteration cannot converge, and the run ends as a
  // failure with its rows before it (it escaped the loop as an exception, rows lost, before).
  SceneSpec spec = parse_scene_file(std::string(CONDYN_SOURCE_DIR) +
                                    "/models/scenes/parallelogram_four_bar.toml");
  spec.solve.t_end = 2.0;
  const test::BuiltScene built = test::built(spec);
  SolveResult result;
  REQUIRE_NOTHROW(result = solve(built.model, test::under(built.spec.solve, Scheme::elimination)));
  REQUIRE(result.failure);
  CHECK(result.failure->in_loop);
  CHECK(result.failure->message.find("coordinate partitioning") != std::string::npos);
  // Ended at the singular time: within a last step of it (observed t = 1.00067, the output row
  // at t = 1 the one that failed).
  CHECK(result.failure->t_reached > 0.5);
  CHECK(result.failure->t_reached < 1.01);
  REQUIRE_FALSE(result.trajectory.t.empty());
  CHECK(result.trajectory.t.back() <= result.failure->t_reached);
}

TEST_CASE("a partition's quality is 1/‖B‖₁, B = [I, −A_d⁻¹ A_i] stacked, against a dense solve") {
  // On A03 (1 independent coordinate: Hager's estimate is exact) and the double pendulum (2),
  // at the output rows of a GGL run: A03's to 0.0095 s, past body1.uy's extreme at 0.0091, where
  // the first partition's quality falls below a tenth of its start. The dense X = A_d⁻¹ A_i by
  // LU; both agree to the solves' roundoff, eps times A_d's condition number (dense SVD) times
  // 64 (a margin over the few operations' accumulation), relative.
  // Not a structured binding: clang 14 (the sanitized build) cannot capture one in CAPTURE's
  // lambda.
  for (const auto& scene_and_end :
       {std::pair{"iftomm/A03_andrews.toml", 0.0095}, std::pair{"double_pendulum.toml", 2.0}}) {
    const char* const name = scene_and_end.first;
    const double t_end = scene_and_end.second;
    CAPTURE(std::string(name));
    const test::BuiltScene built = scene(name, t_end, kRtol);
    const Model& model = built.model;
    const Trajectory run =
        test::solved(model, test::under(built.spec.solve, Scheme::ggl)).trajectory;
    const PartitionedOde first(model, 0.0);
    const CoordinatePartition& p = first.partition();
    auto system = model.evaluator();
    double start = 0.0, smallest = 1.0;
    for (std::size_t k = 0; k < run.t.size(); ++k) {
      const Eigen::MatrixXd A = Eigen::MatrixXd(
          system->constraint_jacobian(run.t[k], run.u.col(static_cast<Eigen::Index>(k))));
      Eigen::MatrixXd ad(A.rows(), static_cast<Eigen::Index>(p.dependent.size()));
      Eigen::MatrixXd ai(A.rows(), static_cast<Eigen::Index>(p.independent.size()));
      for (std::size_t j = 0; j < p.dependent.size(); ++j)
        ad.col(static_cast<Eigen::Index>(j)) = A.col(p.dependent[j]);
      for (std::size_t j = 0; j < p.independent.size(); ++j)
        ai.col(static_cast<Eigen::Index>(j)) = A.col(p.independent[j]);
      const Eigen::MatrixXd X = ad.fullPivLu().solve(ai);
      const double dense = 1.0 / (1.0 + X.cwiseAbs().colwise().sum().maxCoeff());
      const Eigen::VectorXd sv = singular_values(ad);
      const double roundoff =
          64 * std::numeric_limits<double>::epsilon() * sv(0) / sv(sv.size() - 1);
      const double quality = partition_quality(
          system->constraint_jacobian(run.t[k], run.u.col(static_cast<Eigen::Index>(k))), p);
      CAPTURE(run.t[k]);
      CHECK(quality == doctest::Approx(dense).epsilon(roundoff));
      if (k == 0) start = quality;
      smallest = std::min(smallest, quality);
    }
    MESSAGE(std::string(name) << ": quality at the start " << start << ", smallest " << smallest);
    // Below the fraction at which a run leaves the partition: A03's first one is left there.
    if (std::string(name).find("A03") != std::string::npos) {
      CHECK(smallest < PartitionedOde::kRepartitionFraction * start);
    }
  }
}

namespace {

/// hanging_chain.toml's chain with `links` links of length 0.5 (mass 0.1 a joint), released
/// from rest on a line 30 degrees below the horizontal: `links` independent coordinates.
std::string hanging_chain(int links) {
  std::string nodes, masses, members;
  for (int k = 0; k <= links; ++k) {
    nodes += (k ? ", [" : "[") + std::to_string(0.5 * k * std::sqrt(3.0) / 2) + ", " +
             std::to_string(-0.25 * k) + "]";
    masses += k ? ", 0.1" : "0.0";
    if (k > 0) {
      members += (k > 1 ? ", { nodes = [" : "{ nodes = [") + std::to_string(k) + ", " +
                 std::to_string(k + 1) + "], rigid = true }";
    }
  }
  return "[model]\ntype = \"truss2d\"\nnodes = [" + nodes + "]\nmasses = [" + masses +
         "]\nsupports = [1]\nmembers = [" + members +
         "]\ngravity = [0.0, -9.81]\n[solve]\nt_end = 0.2\noutput_step = 0.01\n";
}

}  // namespace

TEST_CASE("coordinate partitioning of a long chain: GMRES on products, no dense Jacobian") {
  // 40 links: 80 unknowns, above the dense Jacobian's 64 (PartitionedOde::kDenseJacobianLimit).
  // CVODE's Newton systems go to GMRES (no matrix: 0 Jacobian entries, where the dense one had
  // 80² = 6400), and the run agrees with GGL at a 100 times tighter rtol within the bound the
  // first case uses (2e4 rtol; O(1) lengths, speeds, forces).
  constexpr int kLinks = 40;
  constexpr double kChainRtol = 1e-8;
  SceneSpec spec = parse_scene_text(hanging_chain(kLinks), "chain.toml");
  spec.solve.rtol = kChainRtol;
  spec.solve.atol = kChainRtol * 1e-2;
  const test::BuiltScene built = test::built(spec);
  SolveSpec tight = test::under(built.spec.solve, Scheme::ggl);
  tight.rtol = 1e-2 * kChainRtol;
  tight.atol = 1e-2 * spec.solve.atol;
  const Trajectory ref = test::solved(built.model, tight).trajectory;
  const SolveResult result =
      test::solved(built.model, test::under(built.spec.solve, Scheme::elimination));
  CHECK(result.summary.unknowns == 2 * kLinks);
  CHECK(result.summary.jacobian_nonzeros == 0);
  CHECK(result.summary.notes_text().find("GMRES on difference-quotient products (80 unknowns") !=
        std::string::npos);
  const TrajectoryError err = relative_error(result.trajectory, ref);
  MESSAGE("chain of " << kLinks << ": err u " << err.displacement << ", v " << err.velocity
                      << ", reaction " << err.reaction << "; " << result.summary.brief());
  CHECK(err.displacement < 2e4 * kChainRtol);
  CHECK(err.velocity < 2e4 * kChainRtol);
  CHECK(err.reaction < 2e4 * kChainRtol);
  CHECK(row_drift(built.model, result.trajectory) <=
        newton_tolerance(built.model, result.trajectory, spec.solve.atol));
}

TEST_CASE("coordinate partitioning of a fully driven mechanism: kinematics and KKT reactions") {
  // The slider-crank with a driven crank: the constraints fix every coordinate (no independent
  // one), so nothing is integrated: positions by Newton at each time, velocities and
  // accelerations from the rows, reactions from the KKT system. Refused before
  // (SchemeNotApplicable). Against GGL at rtol 1e-12: the exact kinematics (slider x = r cos θ +
  // √(l² − r² sin² θ), θ = π/2 + 2πt) to the Newton tolerance, reactions to the bound of the first
  // case (2e4 rtol; forces of O(10) N).
  SceneSpec spec = parse_scene_file(std::string(CONDYN_SOURCE_DIR) +
                                    "/models/scenes/multibody/slider_crank.toml");
  spec.solve.output_step = 0.05;
  const test::BuiltScene built = test::built(spec);
  const Model& model = built.model;
  CHECK_FALSE(scheme_refusal(model, Scheme::elimination).has_value());
  const SolveResult result =
      test::solved(model, test::under(built.spec.solve, Scheme::elimination));
  CHECK(result.summary.unknowns == 0);
  CHECK(result.summary.notes_text().find("0 independent of") != std::string::npos);
  SolveSpec tight = tight_ggl(built.spec.solve);
  const Trajectory ref = test::solved(model, tight).trajectory;
  const TrajectoryError err = relative_error(result.trajectory, ref);
  MESSAGE("fully driven slider-crank: err u " << err.displacement << ", v " << err.velocity
                                              << ", reaction " << err.reaction);
  CHECK(err.displacement < 2e4 * built.spec.solve.rtol);
  CHECK(err.velocity < 2e4 * built.spec.solve.rtol);
  CHECK(err.reaction < 2e4 * built.spec.solve.rtol);
  CHECK(row_drift(model, result.trajectory) <=
        newton_tolerance(model, result.trajectory, built.spec.solve.atol));
}

}  // namespace test_partitioned_elimination
