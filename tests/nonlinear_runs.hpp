#pragma once
// What the runs of nonlinear scenes against a tight GGL run share (coordinate partitioning:
// tests/dae/test_partitioned_elimination*.cpp; the augmented Lagrangian:
// test_augmented_lagrangian_validation.cpp): a scene of models/scenes/ at a given horizon and
// tolerance, the drift measure, partitioning's Newton tolerance and the tight GGL reference.

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "dae/run/solve.hpp"
#include "models/core/constraint_drift.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

namespace condyn::test::nonlinear {

inline test::BuiltScene scene(const std::string& name, double t_end, double rtol) {
  SceneSpec spec = parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/" + name);
  spec.solve.t_end = t_end;
  spec.solve.output_step = t_end / 50;
  spec.solve.rtol = rtol;
  spec.solve.atol = rtol * 1e-2;
  return test::built(spec);
}

/// The run's largest position drift over its output rows, each row's |φ_i| over its largest
/// coefficient at t = 0 (a length: ConstraintDrift::relative_position).
inline double row_drift(const Model& model, const Trajectory& run) {
  ConstraintDrift drift(model);
  double worst = 0.0;
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    (void)drift(run.t[k], run.u.col(static_cast<Eigen::Index>(k)),
                run.v.col(static_cast<Eigen::Index>(k)));
    worst = std::max(worst, drift.relative_position());
  }
  return worst;
}

/// The rtol of the runs measured against tight_ggl (atol rtol/100, as scene() sets it).
constexpr double kRtol = 1e-10;

/// The Newton tolerance of a run at `atol` (default rtol/100, as scene() sets it): 1e-3 atol
/// (elimination_run.cpp's kNewtonMargin), floored at 16 ulps of the coordinates' size
/// (partitioned_ode.cpp's kRoundoffUlps; the largest of the run's |u| and the system's coordinate
/// scale).
inline double newton_tolerance(const Model& model, const Trajectory& run,
                               double atol = kRtol * 1e-2) {
  const double scale = std::max(run.u.cwiseAbs().maxCoeff(), model.system->coordinate_scale());
  return std::max(1e-3 * atol, 16 * std::numeric_limits<double>::epsilon() * scale);
}

/// GGL at rtol 1e-12, atol 1e-14: the reference the partitioned runs are measured against.
inline SolveSpec tight_ggl(const SolveSpec& solve) {
  SolveSpec tight = test::under(solve, Scheme::ggl);
  tight.rtol = 1e-12;
  tight.atol = 1e-14;
  return tight;
}

}  // namespace condyn::test::nonlinear
