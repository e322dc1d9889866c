#pragma once
/// A run in two steps: plan() makes every decision once and returns them as a value (the scheme
/// and why, the treatment of the constraints, the scheme's parameters, the tolerances and the
/// integrator's settings); execute() runs a plan and returns its result. `condyn run`, `info`,
/// `compare`, `check` and Python read the same plan (solve() is the two in one).

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dae/formulations/baumgarte_gains.hpp"
#include "dae/formulations/constraint_treatment.hpp"
#include "dae/formulations/model_scales.hpp"
#include "dae/formulations/penalty_ode.hpp"
#include "dae/formulations/reduced_ode.hpp"
#include "dae/formulations/reduced_system.hpp"
#include "dae/run/factorization_choice.hpp"
#include "dae/run/scheme_choice.hpp"
#include "dae/run/solve_result.hpp"
#include "models/core/model.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

/// Everything decided about one run of a model, before it runs. Plain data: copies share the
/// costly parts (the reduction, the treatment), which are never changed.
struct RunPlan {
  const Model* model = nullptr;  ///< the model planned for (not owned: it outlives the plan)
  /// The run's settings: the caller's, but after auto's fallback those it runs with (GGL with a
  /// multiplier for every row).
  SolveSpec settings;
  Scheme scheme = Scheme::automatic;  ///< the scheme that runs (auto resolved)
  std::string reason;                 ///< why it was chosen ("requested" when named)
  /// Why the requested scheme cannot treat the model (scheme_refusal, or elimination's reduction
  /// refused); execute() throws it as SchemeNotApplicable. Nothing below the tolerances is
  /// planned then.
  std::optional<std::string> refusal;
  /// Auto chose elimination and its reduction cannot be integrated (a reduced mass singular to
  /// roundoff, a group too large for the transform): GGL runs instead; the note saying so, which
  /// is also the reason.
  std::optional<std::string> fallback;
  /// The mixed treatment's rows (eliminated and kept), when the run uses it
  /// (uses_mixed_treatment); null for a multiplier per row, and for the other schemes.
  std::shared_ptr<const ConstraintTreatment> treatment;
  /// Elimination's reduction and its ODE (M̂ factored, checked regular): each run integrates a
  /// copy of the ODE. Null for the other schemes.
  std::shared_ptr<const ReducedSystem> reduced;
  std::shared_ptr<const ReducedOde> reduced_ode;
  BaumgarteGains gains;    ///< Baumgarte's α and β (zero for the other schemes)
  PenaltyWeights weights;  ///< penalty's springs and dampers (zero for the other schemes)
  /// The absolute tolerances per kind of unknown and the rule they came from (the model's scales).
  AbsoluteTolerances tolerances;
  IntegratorSettings integrator;  ///< what the integrator is asked, in numbers (no callbacks)
  /// The factorization of the Newton matrices and why (dae/run/factorization_choice.hpp).
  FactorizationChoice factorization;
  /// Noted before the run: the scheme's parameters (Baumgarte's, penalty's rule), the mixed
  /// treatment's counts. The integrator's own note replaces them (SolveSummary::notes).
  std::vector<RunNote> notes;
  /// Whether the run uses the mixed treatment.
  [[nodiscard]] bool mixed() const { return treatment != nullptr; }
};

/// Plans a run of `model` under `settings` (settings.scheme; auto resolves as choose_scheme).
/// Throws std::invalid_argument for settings that fail SolveSpec::validate(), and std::exception
/// when the scheme cannot be set up for the model. A requested scheme that cannot treat the model
/// is recorded (RunPlan::refusal), not thrown, so that `info` can say so.
[[nodiscard]] RunPlan plan(const Model& model, const SolveSpec& settings);
/// As above, with the costly decisions taken from (and left in) `decisions`, which `info` also
/// sizes every scheme with.
[[nodiscard]] RunPlan plan(const Model& model, const SolveSpec& settings,
                           SchemeDecisions& decisions);

/// The condensed Newton system of the plan's run when its matrix is symmetric positive definite
/// (elimination and penalty on a linear model: K + cj C + cj² M), which CHOLMOD can factor;
/// nullptr for the other schemes and for a refused plan.
[[nodiscard]] std::unique_ptr<NewtonSystem> symmetric_newton_system(const RunPlan& plan);

/// What the integrator is asked for this model under these settings: tolerances per kind of
/// unknown (dae/formulations/model_scales.hpp), first step, output times, load steps, budgets.
[[nodiscard]] IntegratorSettings integrator_settings(const Model& model, const SolveSpec& settings);

/// What the caller observes of a run besides its result.
struct RunHooks {
  bool record_steps = false;  ///< keep the drift at every internal step (Trajectory::steps)
  bool accelerations =
      false;  ///< compute accelerations at the output rows (dae/formulations/acceleration.hpp)
  /// λ at the output rows from acceleration level (dae/formulations/row_multipliers.hpp), so that
  /// reactions mean the same under every scheme; off only where no reaction, multiplier or
  /// acceleration of the rows is used (hooks_for), to spare a solve per row.
  bool reactions = true;
  std::function<void(const Progress&)> on_progress;  ///< for long runs (IntegratorOptions)
  /// When set, every output row goes here as it is computed (a failed run's rows included) and
  /// the result's trajectory holds no n x output-times data: its u, v, reaction and multiplier
  /// are empty; t, drifts and energies stay.
  std::function<void(const TrajectoryRow&)> on_row;
  /// The energy balance at the output rows (TrajectoryRow::balance, docs/energy.md).
  bool energy_balance = false;
};

/// The hooks output `quantities` call for: accelerations, reactions, the energy balance.
[[nodiscard]] RunHooks hooks_for(const std::vector<Quantity>& quantities);

/// Runs `plan` observed by `hooks`. A run that fails returns its failure as data
/// (SolveResult::failure, with a suggestion) and the rows computed before it. Throws
/// SchemeNotApplicable for a plan whose scheme was refused (RunPlan::refusal), and std::exception
/// when the scheme's formulation cannot be set up for the model.
[[nodiscard]] SolveResult execute(const RunPlan& plan, const RunHooks& hooks = {});

}  // namespace condyn
