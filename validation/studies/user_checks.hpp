#pragma once
/// A user's own checks ([[check]] tables, scene-format.md "Checks for a user's own validation
/// suite"): run a scene and evaluate each check on the rows as they are computed, keeping only the
/// figures the checks need (nothing of size DOFs x output times). Used by `condyn check`
/// (src/reports/check_report.hpp) and the Python module.

#include <optional>
#include <string>
#include <vector>

#include "dae/run/mapped_rows.hpp"
#include "dae/run/solve_result.hpp"
#include "dae/run/trajectory.hpp"
#include "models/core/model.hpp"
#include "models/core/result_columns.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn {

/// Where a check's column comes from in a row (find_column: models/core/result_columns.hpp).
using CheckColumn = ResultColumn;

/// The outcome of one check.
struct CheckOutcome {
  std::string quantity;
  CheckSpec::Form form = CheckSpec::Form::max_abs;
  double computed = 0.0;  ///< the figure compared with `bound` (NaN when it could not be formed)
  double bound = 0.0;     ///< tolerance or max_abs
  bool passed = false;
  std::string text;  ///< one line: what was computed against what
};

/// Evaluates checks on rows as they come (RunHooks::on_row). The columns are resolved when it is
/// made: an unknown one is refused with SceneError naming the scene, the check's line and key.
class CheckEvaluator {
 public:
  CheckEvaluator(const Model& model, const std::vector<CheckSpec>& checks, const std::string& file);
  void add(const TrajectoryRow& row);
  [[nodiscard]] std::vector<CheckOutcome> outcomes() const;
  /// The output quantities the checks read (to switch on in [output] before the run).
  [[nodiscard]] std::vector<Quantity> quantities() const;

 private:
  struct State {
    CheckColumn column;
    double figure = 0.0;    ///< running max, or the value at `at`
    bool seen = false;      ///< `at` reached / any row seen
    double distance = 0.0;  ///< `at`: |t − at| of the row kept
    std::size_t next = 0;   ///< reference: its next row to compare
    double previous_t = 0.0, previous_value = 0.0;
    bool has_previous = false;
  };
  [[nodiscard]] double value(const TrajectoryRow& row, const CheckColumn& c) const;

  const Model* model_;
  std::vector<CheckSpec> checks_;
  std::vector<State> states_;
  /// A mechanism's rows in its output map's columns, with the points the checks read.
  std::optional<MappedRows> mapper_;
  std::vector<int> points_;  ///< the map's indices of those points, in the mapped row's order
  TrajectoryRow mapped_;
};

/// One outcome per check of a run that failed before t_end: computed NaN, the check's bound,
/// passed false, and text saying it was not evaluated (condyn.check's `checks`; the command
/// prints the failure alone).
[[nodiscard]] std::vector<CheckOutcome> unevaluated_outcomes(const std::vector<CheckSpec>& checks);

struct SceneCheckOptions {
  std::optional<Scheme> scheme;  ///< overrides [solve] scheme
  SourcePoint scheme_where;      ///< where the override comes from (`--scheme`), for refusals
  std::optional<double> step;    ///< overrides [solve] step (the Newmark family's fixed step)
};

/// One scene's run and its checks.
struct SceneCheckResult {
  std::string scene;
  std::string scheme;  ///< the scheme that ran
  long steps = 0;
  double wall_s = 0.0;  ///< the solver's wall time
  std::string failure;  ///< the integration failure's message, empty when the run reached t_end
  std::vector<std::string> warnings;  ///< what building the model warned of, as run prints it
  /// The run's drift warning (SolveSummary::drift_warning), empty when none: the constraints
  /// were not held to the tolerance, a failed verdict of its own whatever the checks say.
  std::string drift;
  std::vector<CheckOutcome> outcomes;  ///< empty when the run failed
  [[nodiscard]] bool passed() const;
};

/// Switches on in [output] what the checks' energy columns need, before the build.
void add_check_quantities(SceneSpec& spec);
/// `quantities` with those the evaluator's checks read (for the run's hooks).
[[nodiscard]] std::vector<Quantity> with_check_quantities(std::vector<Quantity> quantities,
                                                          const CheckEvaluator& evaluator);
/// The verdict of a run whose rows `evaluator` has seen: its outcomes (none when the run failed:
/// `failure` says why), its drift warning, the build's `warnings` and the singular passages'.
[[nodiscard]] SceneCheckResult check_verdict(const std::string& file, const SolveSpec& settings,
                                             const SolveResult& result,
                                             const CheckEvaluator& evaluator,
                                             std::vector<std::string> warnings);

/// Parses the scene, switches on the quantities its checks read, builds, runs and evaluates.
/// Throws SceneError for bad input (a scene without [[check]] included), and what solve() throws.
[[nodiscard]] SceneCheckResult run_scene_checks(const std::string& path,
                                                const SceneCheckOptions& options = {});
/// The same for a scene already parsed (its `file` names it in messages).
[[nodiscard]] SceneCheckResult run_scene_checks(SceneSpec spec,
                                                const SceneCheckOptions& options = {});

}  // namespace condyn
