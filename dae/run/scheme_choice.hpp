#pragma once
/// Which scheme a run uses and why, what each scheme cannot treat, and what each makes the
/// integrator solve (its size): the decisions a run plan (dae/run/run_plan.hpp) and `condyn info`
/// are made of.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dae/formulations/constraint_treatment.hpp"
#include "dae/formulations/reduced_ode.hpp"
#include "dae/formulations/reduced_system.hpp"
#include "dae/interface/scheme_not_applicable.hpp"
#include "models/core/model.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

struct SchemeChoice {
  Scheme scheme = Scheme::elimination;
  std::string reason;  ///< why this scheme (printed by `condyn info`)
};

/// Why `scheme` cannot treat this model (elimination on nonholonomic rows, penalty on nonlinear
/// models), or
/// nothing when it can.
[[nodiscard]] std::optional<std::string> scheme_refusal(const Model& model, Scheme scheme);

/// Throws SchemeNotApplicable with scheme_refusal()'s reason and `chosen_at` when `scheme` is
/// refused.
void refuse_inapplicable(const Model& model, Scheme scheme, const SourcePoint& chosen_at);

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

/// The costly decisions about runs of one model, each made once and shared by whoever holds this:
/// a plan (dae/run/run_plan.hpp) and `info`'s table of sizes. The treatment of the constraints
/// (treat_constraints: a master-slave transform per group), elimination's reduction (reduce: the
/// transform of all rows) and its ODE (M̂ factored), and the mixed treatment's reduced system,
/// the same under every multiplier scheme (on large models each is a large part of `info`'s
/// time: docs/benchmarks.md).
/// Slaves are [solve] slaves, the same in every call.
class SchemeDecisions {
 public:
  explicit SchemeDecisions(const Model& model) : model_(model) {}
  /// What settings.scheme makes the integrator solve (system_size).
  [[nodiscard]] SystemSize size(const SolveSpec& settings);
  /// What `resolved` (not auto) makes the integrator solve under `settings`, whose scheme may be
  /// auto (the mixed treatment follows it: uses_mixed_treatment).
  [[nodiscard]] SystemSize size_as(Scheme resolved, const SolveSpec& settings);
  /// Resolves settings.scheme as choose_scheme() does, with the treatment and the sizes made here.
  [[nodiscard]] SchemeChoice choose(const SolveSpec& settings);
  /// treat_constraints(model), made on first use. Throws like it.
  [[nodiscard]] const std::shared_ptr<const ConstraintTreatment>& treatment();
  /// reduce(model, slaves), made on first use. Throws like it.
  [[nodiscard]] const std::shared_ptr<const ReducedSystem>& reduced(
      const std::vector<std::string>& slaves);
  /// The reduction's ODE, made on first use (it refers to reduced(): keep both): building it
  /// factors M̂, and refuses
  /// (SchemeNotApplicable) a reduction it cannot integrate. Throws like ReducedOde().
  [[nodiscard]] const std::shared_ptr<const ReducedOde>& reduced_ode(
      const std::vector<std::string>& slaves);
  /// Frees the reduction and its ODE here (those a plan holds stay with it).
  void release_reduced() {
    reduced_ode_.reset();
    reduced_.reset();
  }

 private:
  const Model& model_;
  std::shared_ptr<const ConstraintTreatment> treatment_;
  std::shared_ptr<const ReducedSystem> reduced_;
  std::shared_ptr<const ReducedOde> reduced_ode_;
  /// Set on first use: the reduced system, or null when the treatment eliminates no row.
  std::optional<std::shared_ptr<const MechanicalSystem>> mixed_;
};

}  // namespace condyn
