#pragma once
/// Scheme choice and dispatch: the one entry point the CLI and the validation suite use.

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "dae/interface/scheme_not_applicable.hpp"
#include "dae/run/solve_result.hpp"
#include "models/core/model.hpp"
#include "models/core/output_quantity.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

struct SchemeChoice {
  Scheme scheme = Scheme::elimination;
  std::string reason;  ///< why this scheme (printed by `condyn info`)
};

/// Why `scheme` cannot treat this model (elimination and penalty on nonlinear models), or
/// nothing when it can.
[[nodiscard]] std::optional<std::string> scheme_refusal(const Model& model, Scheme scheme);

/// Resolves settings.scheme. auto: GGL for a nonlinear model (its constant linear rows
/// eliminated where that stays sparse, unless [solve] constraints = "multipliers"); for a linear
/// one, elimination when every constraint group's transform stays sparse, else GGL with the
/// mixed treatment (dae/formulations/constraint_treatment.hpp). With constraints = "multipliers",
/// the cheaper of elimination and GGL by the nonzeros of the Newton matrix each factors at every
/// Jacobian update (system_size, with settings.slaves).
[[nodiscard]] SchemeChoice choose_scheme(const Model& model, const SolveSpec& settings);

/// Whether a run under `resolved` (a scheme, not auto) eliminates the constant linear rows whose
/// transform stays sparse and keeps multipliers for the rest
/// (dae/formulations/constraint_treatment.hpp): [solve] constraints = "mixed", or unset with scheme
/// auto; multiplier schemes only.
[[nodiscard]] bool uses_mixed_treatment(const Model& model, Scheme resolved,
                                        const SolveSpec& settings);
/// The treatment of the constraints in a run under `resolved`, by [solve] constraints' names:
/// "mixed" or "multipliers" for a multiplier scheme on a model with constraints, else nullptr
/// (the HDF5 attribute `constraints`, the Python summary's "constraints").
[[nodiscard]] const char* treatment_name(const Model& model, Scheme resolved,
                                         const SolveSpec& settings);

struct ReducedSystem;  // dae/run/elimination.hpp

/// What a scheme makes the integrator solve for this model.
struct SystemSize {
  int unknowns = 0;
  long jacobian_nonzeros = 0;  ///< of the matrix the Newton iterations factor
  /// That matrix is the condensed one (positions eliminated: the projection's saddle point,
  /// [solve] newton = "condensed"), not the integrator's Jacobian over [u; v; ...].
  bool condensed = false;
  /// That matrix is dense ([solve] linear_solver = "dense", the projection of a nonlinear model):
  /// unknowns² entries, factored without KLU.
  bool dense = false;
  /// The system is a reduced model's (elimination, the mixed treatment): its matrices are held
  /// beside the model's.
  bool reduced = false;
};

/// Builds the DAE of settings.scheme (without integrating) and sizes it. Throws like solve().
[[nodiscard]] SystemSize system_size(const Model& model, const SolveSpec& settings);

/// system_size for many settings of one model (`info`'s table): the mixed treatment's reduced
/// system (dae/formulations/eliminated_system.hpp), the same under every multiplier scheme, is
/// built once, not once per scheme: on large models it is a large part of `info`'s time
/// (docs/benchmarks.md).
class SystemSizer {
 public:
  explicit SystemSizer(const Model& model) : model_(model) {}
  [[nodiscard]] SystemSize operator()(const SolveSpec& settings);
  /// The elimination path's master-slave reduction for `slaves` ([solve] slaves, the same in
  /// every call), made once: sizing elimination and `info`'s list of slaves and masters share it
  /// (at 10⁶ DOFs each reduction is a share of `info`'s time). Throws like reduce().
  [[nodiscard]] const ReducedSystem& reduced(const std::vector<std::string>& slaves);
  /// Frees the reduction (the next reduced() makes it again).
  void release_reduced() { reduced_.reset(); }

 private:
  const Model& model_;
  std::shared_ptr<const ReducedSystem> reduced_;
  /// Set on first use: the reduced system, or null when the treatment eliminates no row.
  std::optional<std::shared_ptr<const MechanicalSystem>> mixed_;
};

/// What the integrator is asked to do for this model under these settings: tolerances per kind of
/// unknown (dae/formulations/model_scales.hpp), first step, output times, load steps, budgets.
[[nodiscard]] IntegratorOptions integrator_options(const Model& model, const SolveSpec& settings);

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

/// Solves the model under settings.scheme (`automatic` resolves through choose_scheme) with the
/// run's settings (tolerances, budgets, times, scheme parameters). A run that fails returns its
/// failure as data (SolveResult::failure, with a suggestion) and the rows computed before it.
/// Throws SchemeNotApplicable for a scheme that cannot treat the model, std::invalid_argument
/// for settings that fail SolveSpec::validate(), and std::exception when the scheme cannot be set
/// up for the model (a singular reduced mass, say).
[[nodiscard]] SolveResult solve(const Model& model, const SolveSpec& settings,
                                const RunHooks& hooks = {});

}  // namespace condyn
