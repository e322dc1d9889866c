// Elimination of nonlinear models by coordinate partitioning (dae/formulations/partitioned_ode.hpp)
// over whole runs against a tight GGL run: the pendulum, the four-bar and the double pendulum, the
// constraints held to the Newton tolerance by construction; re-partitions where the first
// partition's dependent block turns singular (the four-bar, Andrews' mechanism); GMRES against
// the dense Jacobian on the four-bar (11 s under the sanitizers). Validation tier:
// long runs at tight tolerances, run optimized (test_partitioned_elimination.cpp holds the unit
// cases, which reach every line of the library these do under the sanitizers).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>

#include <Eigen/Dense>

#include "dae/formulations/coordinate_partition.hpp"
#include "dae/formulations/partitioned_ode.hpp"
#include "dae/integrators/cvode_integrator.hpp"
#include "dae/run/scheme_choice.hpp"
#include "dae/run/solve.hpp"
#include "dae/run/trajectory.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/nonlinear_runs.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"

using namespace condyn;

namespace test_partitioned_elimination_validation {

using namespace condyn::test::nonlinear;

TEST_CASE("elimination by coordinate partitioning agrees with GGL on nonlinear scenes") {
  // Over 2 s (the double pendulum is chaotic) at rtol 1e-10 (atol 1e-12) against GGL at rtol 1e-12
  // (atol 1e-14), the bounds of the other schemes on these scenes
  // (tests/validation/test_nonlinear_validation.cpp): 2e4 × rtol in u, v and the reactions (O(1)
  // lengths, speeds and forces), 1e4 × rtol in energy. Observed: see the MESSAGE lines (-s).
  for (const char* name : {"pendulum.toml", "four_bar.toml", "double_pendulum.toml"}) {
    CAPTURE(std::string(name));
    const test::BuiltScene built = scene(name, 2.0, kRtol);
    const Model& model = built.model;
    REQUIRE_FALSE(scheme_refusal(model, Scheme::elimination).has_value());
    SolveSpec tight = tight_ggl(built.spec.solve);
    const Trajectory ref = test::solved(model, tight).trajectory;
    const SolveResult result =
        test::solved(model, test::under(built.spec.solve, Scheme::elimination));
    CHECK(result.scheme == Scheme::elimination);
    const Trajectory& run = result.trajectory;
    const TrajectoryError err = relative_error(run, ref);
    const double energy = relative_energy_error(run);
    const double drift = row_drift(model, run);
    MESSAGE(std::string(name) << ": err u " << err.displacement << ", v " << err.velocity
                              << ", reaction " << err.reaction << ", energy " << energy
                              << ", drift " << drift << "; " << result.summary.notes_text());
    CHECK(err.displacement < 2e4 * kRtol);
    CHECK(err.velocity < 2e4 * kRtol);
    CHECK(err.reaction < 2e4 * kRtol);
    CHECK(energy >= 0.0);
    CHECK(energy < 1e4 * kRtol);
    // Every row holds to the Newton tolerance at every state the run reports, by construction
    // (GGL's drift, for scale, is held at its own Newton tolerance near rtol).
    CHECK(drift <= newton_tolerance(model, run));
    CHECK(result.summary.notes_text().find("coordinate partitioning: ") != std::string::npos);
  }
}

TEST_CASE("coordinate partitioning re-partitions where the first dependent block turns singular") {
  // The crank of four_bar.toml turns fully (Grashof), so each of its tip's coordinates reaches an
  // extreme, where it can no longer be solved for: the first partition's dependent block turns
  // singular along the motion. Shown on GGL's reference run, then passed by elimination.
  const test::BuiltScene built = scene("four_bar.toml", 2.0, kRtol);
  const Model& model = built.model;
  SolveSpec tight = tight_ggl(built.spec.solve);
  tight.output_step = 1e-3;  // fine enough to sample the block's conditioning near its zero
  const Trajectory ref = test::solved(model, tight).trajectory;
  const PartitionedOde first(model, 0.0);
  auto system = model.evaluator();
  double smallest = 1.0;
  for (std::size_t k = 0; k < ref.t.size(); ++k) {
    const auto& A = system->constraint_jacobian(ref.t[k], ref.u.col(static_cast<Eigen::Index>(k)));
    smallest = std::min(smallest, partition_quality(A, first.partition()));
  }
  // The partition's quality at t = 0 is of order 1; at the output closest to the singular
  // position it is below 1e-2 (at 1 ms sampling, a crank at 6 rad/s passes within 0.006 rad of
  // it); observed in the MESSAGE.
  MESSAGE("first partition's smallest quality along the reference: " << smallest);
  CHECK(smallest < 1e-2);

  const SolveResult result =
      test::solved(model, test::under(built.spec.solve, Scheme::elimination));
  const std::string notes = result.summary.notes_text();
  CAPTURE(notes);
  CHECK(notes.find(" re-partition") != std::string::npos);
  CHECK(notes.find("no re-partition") == std::string::npos);
  // Through the passages the run stays with GGL's (bounds as above: 2e4 × rtol).
  SolveSpec tight_rows = tight;
  tight_rows.output_step = built.spec.solve.output_step;
  const Trajectory ref_rows = test::solved(model, tight_rows).trajectory;
  const TrajectoryError err = relative_error(result.trajectory, ref_rows);
  MESSAGE("err u " << err.displacement << ", v " << err.velocity << ", reaction " << err.reaction);
  CHECK(err.displacement < 2e4 * kRtol);
  CHECK(err.velocity < 2e4 * kRtol);
  CHECK(err.reaction < 2e4 * kRtol);
  CHECK(row_drift(model, result.trajectory) <= newton_tolerance(model, result.trajectory));
}

TEST_CASE("coordinate partitioning passes the turning crank of Andrews' mechanism (IFToMM A03)") {
  // body1 turns 2.5 times in the benchmark's 0.03 s. The first partition makes body1.uy (the sine
  // of its angle) independent, and it reaches its extreme at t = 0.0091: there the run failed
  // (CV_CONV_FAILURE, the Newton iteration finding no dependent coordinates past uy = 1) while
  // the dependent block's pivot ratio decided, which a constant small pivot of the block kept
  // within 13 % of its start up to the failure. The partition's quality falls like the cosine
  // of the angle: the run re-partitions onto body1.ux before the extreme. Over 0.012 s, past it,
  // at rtol 1e-10 against GGL at rtol 1e-12, within the first case's bounds (2e4 rtol).
  const test::BuiltScene built = scene("iftomm/A03_andrews.toml", 0.012, kRtol);
  const Model& model = built.model;
  SolveSpec tight = tight_ggl(built.spec.solve);
  const Trajectory ref = test::solved(model, tight).trajectory;
  const SolveResult result =
      test::solved(model, test::under(built.spec.solve, Scheme::elimination));
  const std::string notes = result.summary.notes_text();
  CAPTURE(notes);
  CHECK(notes.find("independent of 28 coordinates at the start (body1.uy)") != std::string::npos);
  CHECK(notes.find("(body1.ux independent, body1.uy dependent") != std::string::npos);
  const TrajectoryError err = relative_error(result.trajectory, ref);
  MESSAGE("A03: err u " << err.displacement << ", v " << err.velocity << ", reaction "
                        << err.reaction << "; " << notes);
  CHECK(err.displacement < 2e4 * kRtol);
  CHECK(err.velocity < 2e4 * kRtol);
  CHECK(err.reaction < 2e4 * kRtol);
  CHECK(row_drift(model, result.trajectory) <= newton_tolerance(model, result.trajectory));
}

TEST_CASE("coordinate partitioning: GMRES and the dense Jacobian agree on a small mechanism") {
  // The four-bar (2 unknowns) integrated both ways, forced: the same ODE, so the runs differ by
  // the error control's choices only, each within rtol-scaled global error of the solution:
  // bounded by the first case's 2e4 rtol.
  const test::BuiltScene built = scene("four_bar.toml", 1.0, kRtol);
  std::array<Eigen::VectorXd, 2> end;
  for (const bool free : {false, true}) {
    PartitionedOde ode(built.model, 0.0);
    ode.set_newton_tolerance(1e-3 * built.spec.solve.atol);
    ode.set_matrix_free(free);
    IntegratorOptions o;
    o.output_times = {0.0, 0.5, 1.0};
    o.rtol = built.spec.solve.rtol;
    o.atol = built.spec.solve.atol;
    SolveSummary s;
    const RawTrajectory raw = integrate_ode(ode, ode.initial_state(), o, s);
    CHECK(s.jacobian_nonzeros == (free ? 0 : 4));
    end.at(free ? 1 : 0) = ode.full(1.0, raw.y.back()).u;
  }
  CHECK((end[1] - end[0]).lpNorm<Eigen::Infinity>() <
        2e4 * kRtol * end[0].lpNorm<Eigen::Infinity>());
}

}  // namespace test_partitioned_elimination_validation
