#pragma once
/// `condyn compare`: one scene under every scheme across a tolerance sweep, each run repeated for
/// a stable wall time, errors against the best reference available, drift logs and multiplier
/// histories at one tolerance, and a Baumgarte gain study. Output files:
/// src/reports/compare_output.hpp and validation/compare-output.md.

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <cmath>
#include <limits>
#include <optional>

#include "dae/run/trajectory.hpp"
#include "models/scene/scene_spec.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/studies/drift_growth.hpp"

namespace condyn {

/// Median (the mean of the middle two for an even count), minimum and maximum of repeated wall
/// times. Throws std::invalid_argument for no timings.
struct WallStatistics {
  double median = 0.0, min = 0.0, max = 0.0;
};
[[nodiscard]] WallStatistics wall_statistics(std::vector<double> walls);

struct CompareOptions {
  /// The ranges validate() holds, the command line's and Python's alike.
  static constexpr int kMaxRepeats = 100;
  static constexpr double kMinDriftRtol = 1e-14, kMaxDriftRtol = 0.5;
  static constexpr double kMinWallTime = 1e-9, kMaxWallTime = 1e12;  ///< a budget, when given
  std::vector<double> tolerances = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  /// atol = rtol · atol_ratio (the scene's atol/rtol when not set).
  double atol_ratio = 0.0;
  int repeats = 3;  ///< runs per (scheme, rtol); wall time median and spread over them
  std::vector<Scheme> schemes = {std::begin(kSchemes), std::end(kSchemes)};
  double drift_rtol = 1e-6;  ///< tolerance of the drift, history and Baumgarte-study runs
  /// Gains of the Baumgarte study: default α and β times each factor (a grid).
  std::vector<double> baumgarte_factors = {0.1, 1.0, 10.0, 100.0};
  /// Run the Baumgarte study at all (compare --baumgarte-study): 16 runs, some of up to a million
  /// steps on mechanisms, so it is asked for, not done by default.
  bool baumgarte_study = false;
  /// Budget of every run of the sweep, the histories and the study (not the reference): internal
  /// steps and wall seconds (0: none), as [solve] max_steps and max_wall_time. A run beyond it is
  /// a failed run, recorded with the reason, and the sweep goes on.
  long max_steps = 0;
  double max_wall_time = 0.0;
  /// A run whose worst error (error_u, error_v, error_reaction) exceeds mark_factor times its
  /// target (RunRecord::error_target) is marked over_tolerance: well beyond the spread of
  /// global error over rtol of the schemes that converge (up to 1e3 on the example scenes from
  /// rtol 1e-3 to 1e-10, index3 6.3e3 on the shear frame at 1e-10). compare --fail-above sets it
  /// and fails such runs.
  static constexpr double kDefaultMarkFactor = 1e4;
  double mark_factor = kDefaultMarkFactor;
  /// Called after every run with a one-line progress note.
  std::function<void(const std::string&)> progress;
  /// Throws std::invalid_argument naming the bad option ("tolerances: ..."): each tolerance in
  /// [kMinRtol, 1) and listed once, repeats in [1, kMaxRepeats], drift_rtol in [kMinDriftRtol,
  /// kMaxDriftRtol], max_steps in [0, 2^31 − 1], max_wall_time 0 (none) or in [kMinWallTime,
  /// kMaxWallTime], mark_factor in [1, 1e15].
  void validate() const;
};

struct RunRecord {
  Scheme scheme = Scheme::elimination;
  double rtol = 0.0, atol = 0.0;
  bool ok = false;
  std::string message;  ///< failure text
  double error_u = 0.0, error_v = 0.0, error_reaction = 0.0;
  double max_drift_position = 0.0, max_drift_velocity = 0.0;
  double final_drift_position = 0.0, final_drift_velocity = 0.0;
  long steps = 0, residual_evals = 0, jacobian_evals = 0, newton_failures = 0,
       error_test_failures = 0;
  double wall_median = 0.0, wall_min = 0.0, wall_max = 0.0;
  int repeats = 0;
  /// Against a published reference (built-in benchmarks): the test set's significant correct
  /// digits at the final time, positions and velocities; NaN without one.
  double mescd_u = std::numeric_limits<double>::quiet_NaN();
  double mescd_v = std::numeric_limits<double>::quiet_NaN();
  /// Conservative scenes: max |E(t) − E(0)| relative to the energy scale; NaN otherwise.
  double energy_error = std::numeric_limits<double>::quiet_NaN();
  /// The error the run aims at: its rtol; under penalty, whose error its weight sets and rtol
  /// does not, max(rtol, kPenaltyAccuracy · w_default / w).
  double error_target = 0.0;
  /// The worst of error_u, error_v and error_reaction over error_target (NaN for a failed run),
  /// and whether it exceeds CompareOptions::mark_factor.
  double error_ratio = std::numeric_limits<double>::quiet_NaN();
  bool over_tolerance = false;
};

/// Penalty's default weight (1e4 times the stiffest diagonal) aims at constraint errors of about
/// 1e-4 of the elastic deformation, and its errors shrink like 1/w (docs/schemes.md).
inline constexpr double kPenaltyAccuracy = 1e-4;

/// Reference rows per output interval: the reference is computed on the output grid refined by
/// this, and the error scales (ErrorScales) are its largest values over all of it, so that a
/// quantity zero at every output row (a pendulum's rod force at its turning points, sampled
/// once a swing) is still measured against its size over the run. A power of two: the output
/// times are among the refined ones bit for bit.
inline constexpr int kScaleSamples = 4;

/// One scheme's run at drift_rtol: its per-step drift log and its output-time trajectory.
struct SchemeHistory {
  Scheme scheme = Scheme::elimination;
  bool ok = false;
  std::string message;
  double t_reached = 0.0;        ///< where the run stopped (t_end when it succeeded)
  Trajectory trajectory;         ///< a failed run's rows and steps before the failure
  DriftGrowthAssessment growth;  ///< drift ∝ t^p from the per-step log, where meaningful
};

struct BaumgarteStudyPoint {
  double alpha = 0.0, beta = 0.0;
  bool is_default = false, ok = false;
  std::string message;
  double max_drift_position = 0.0, max_drift_velocity = 0.0, wall = 0.0;
  long steps = 0;
  /// Relative max-norm displacement error against the reference trajectory (NaN against a
  /// published reference, which has no trajectory).
  double error_u = std::numeric_limits<double>::quiet_NaN();
};

/// No run of the sweep can be scored: no exact or published solution, and the tight reference
/// runs failed (what() says which and why, and what to change).
class NoReferenceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CompareResult {
  std::string scene_name;
  /// "exact", "elimination", "ggl" (trajectories), or "published" (a built-in benchmark's
  /// reference state at the final time: errors are then at that time only).
  std::string reference_kind;
  int trusted_digits_u = 0, trusted_digits_v = 0;  ///< "published" only
  std::string reference_description;               ///< how the reference was obtained
  CompareOptions options;
  /// Requested schemes that cannot treat the scene (elimination and penalty on nonlinear
  /// models), with the reason: not run, and not counted as failures.
  std::vector<std::pair<Scheme, std::string>> skipped;
  /// What building the model warned of (BuildReport::warnings), as run prints it.
  std::vector<std::string> warnings;
  /// What the errors are relative to (accuracy.hpp): the largest |u|, |u'|, |f_con| and the energy
  /// scale over the reference sampled kScaleSamples times per output interval (against a
  /// published state, over a run at drift_rtol so sampled), and where they come from. All 0
  /// when no scale run succeeded against a published state: each run's own rows then.
  ErrorScales error_scales;
  std::string scale_source;
  std::vector<RunRecord> runs;
  std::vector<SchemeHistory> histories;
  std::vector<BaumgarteStudyPoint> baumgarte_study;
  /// The reference's multipliers (m x nt) at its times, for differences against it; empty for a
  /// published reference.
  std::vector<double> reference_t;
  Eigen::MatrixXd reference_multiplier;
  std::vector<std::string> constraint_names;
  /// The reaction columns of the histories: name and row of Trajectory::reaction. The DOFs some
  /// constraint touches (`reaction_ux1`), or a mechanism's joint reactions (`hinge.fx`: its
  /// histories hold its output map's columns, dae/run/mapped_rows.hpp).
  std::vector<std::pair<std::string, int>> reaction_columns;
  /// Runs of the sweep and histories that failed (the study's points are not counted: extreme
  /// gains are meant to find where it breaks).
  [[nodiscard]] int failed_runs() const;
  /// Runs of the sweep marked over_tolerance.
  [[nodiscard]] int over_tolerance_runs() const;
};

/// Runs the comparison. A failed run is recorded, not thrown; input errors throw SceneError, and
/// SchemeNotApplicable when no requested scheme can treat the scene.
[[nodiscard]] CompareResult run_compare(const SceneSpec& spec, const CompareOptions& options);

}  // namespace condyn
