#pragma once
/// Each scheme's runner, beside its formulation: it builds the formulation a plan names, its
/// initial state and how its state maps to what the model observes, and hands them to the one
/// observed run (dae/run/observed_run.hpp) that execute() passes in. The runners decide nothing:
/// the scheme, its parameters and the constraint treatment come from the plan
/// (dae/run/run_plan.hpp).

#include <Eigen/Dense>
#include <functional>
#include <utility>

#include "dae/formulations/baumgarte_gains.hpp"
#include "dae/formulations/constraint_treatment.hpp"
#include "dae/formulations/penalty_ode.hpp"
#include "dae/formulations/reduced_ode.hpp"
#include "dae/integrators/step_driver.hpp"
#include "models/core/model.hpp"
#include "models/core/newmark_parameters.hpp"

namespace condyn {

/// How a scheme's state y maps to what the model observes.
struct Observation {
  using FullState = std::function<std::pair<Eigen::VectorXd, Eigen::VectorXd>(
      double t, const Eigen::VectorXd& y)>;
  /// u and u' in full DOF space at (t, y).
  FullState full_state;
  /// λ at an output (t, y, y'), whose full-space u and u' are given.
  std::function<Eigen::VectorXd(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                const Eigen::VectorXd& u, const Eigen::VectorXd& v)>
      multipliers;
  /// λ at an output row, when it differs from `multipliers` (which the energy balance's
  /// integrand keeps at every quadrature point); optional.
  std::function<Eigen::VectorXd(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                const Eigen::VectorXd& u, const Eigen::VectorXd& v)>
      row_multipliers;
  /// Further per-step observation of y (GGL's μ); optional.
  std::function<void(const Eigen::VectorXd& y)> on_state;
  /// What the per-step observation adds to the run's summary once the run has ended, failed or
  /// not (GGL's largest |μ|); optional.
  std::function<void(SolveSummary& summary)> on_finish;
  /// Measure the drift at every internal step even without a drift log (the multiplier schemes,
  /// whose drift between outputs is what they are judged by). Elimination satisfies the
  /// constraints by construction and pays for the per-step map only when a log is asked for.
  bool drift_at_every_step = true;
};

/// Integrates a scheme's formulation with `options` (the observed run's: its observers added),
/// counting into `summary`.
using Integrate =
    std::function<RawTrajectory(const IntegratorOptions& options, SolveSummary& summary)>;
/// Runs `integrate` observed by `observe` into the run's result (execute() binds it to the model,
/// the options and the result: dae/run/observed_run.hpp).
using ObservedRun = std::function<void(const Integrate& integrate, const Observation& observe)>;

class AccelerationLevelMultipliers;
class EliminatedSystem;

/// Sets observe.row_multipliers to λ at the output rows from acceleration level
/// (dae/formulations/row_multipliers.hpp), on the system the scheme integrates, whose state y
/// starts with [u; v] of n DOFs each (the reduced one under the mixed treatment, `observer`,
/// whose eliminated rows' λ follow; null otherwise); the scheme's own λ (observe.multipliers)
/// where that solve fails. `at_rows` and `observer` must outlive the run.
void observe_row_multipliers(AccelerationLevelMultipliers& at_rows, EliminatedSystem* observer,
                             int n, Observation& observe);

/// The full-state map of a scheme whose state starts with [u; v] (every scheme but elimination).
[[nodiscard]] Observation::FullState full_state_prefix(int n);

/// The run of a first-order scheme (penalty, projection) whose state y = [u; v] starts at the
/// model's u0 and v0 and whose λ at an output comes from its formulation at (t, y):
/// `integrate_from` integrates it from a given y0.
using StateMultipliers = std::function<Eigen::VectorXd(double t, const Eigen::VectorXd& y)>;
using IntegrateFrom = std::function<RawTrajectory(
    const Eigen::VectorXd& y0, const IntegratorOptions& options, SolveSummary& summary)>;
void run_first_order(const Model& model, const StateMultipliers& multipliers,
                     const IntegrateFrom& integrate_from, const ObservedRun& run);

/// The multiplier schemes (index1, baumgarte, ggl, index2, index3) with IDA
/// (dae/formulations/multiplier_dae.hpp). `gains`: Baumgarte's (zero for the others). `mixed`:
/// the mixed treatment's rows (dae/formulations/eliminated_system.hpp), or null for a multiplier
/// per row. `row_multipliers`: λ at the output rows from acceleration level
/// (dae/formulations/row_multipliers.hpp).
void run_multipliers(const Model& model, Scheme scheme, const BaumgarteGains& gains,
                     const ConstraintTreatment* mixed, bool row_multipliers,
                     const ObservedRun& run);

/// Penalty with IDA (dae/formulations/penalty_ode.hpp) on a linear model; on a nonlinear one the
/// augmented Lagrangian with CVODE (dae/formulations/augmented_lagrangian_ode.hpp), `weights`
/// unused.
void run_penalty(const Model& model, const PenaltyWeights& weights, const ObservedRun& run);

/// Projection with CVODE (dae/formulations/projected_ode.hpp).
void run_projection(const Model& model, const ObservedRun& run);

/// The Newmark family (newmark, hht, generalized_alpha) with the fixed step `step`, or with
/// error-controlled steps at the run's rtol and atol when `step` is 0
/// (dae/integrators/newmark_stepper.hpp), its constraints at index 3 or stabilized
/// (`constraints`). `mixed`: as for the multiplier schemes, the rows to eliminate (null or none
/// eliminated: a multiplier per row). `row_multipliers`: λ at the output rows from acceleration
/// level (dae/formulations/row_multipliers.hpp), as the multiplier schemes report theirs;
/// otherwise (and within the energy balance's integrals) the step's own λ.
void run_newmark(const Model& model, const AlphaParameters& parameters,
                 NewmarkConstraints constraints, double step, const ConstraintTreatment* mixed,
                 bool row_multipliers, const ObservedRun& run);

/// RATTLE with the fixed step `step` (dae/integrators/rattle_stepper.hpp). `row_multipliers`: λ
/// at the output rows from acceleration level (dae/formulations/row_multipliers.hpp), as the
/// multiplier schemes report it; otherwise the last velocity stage's multiplier.
void run_rattle(const Model& model, double step, bool row_multipliers, const ObservedRun& run);

/// Elimination with IDA: `ode` integrates `reduced` (dae/formulations/reduced_ode.hpp), the
/// reduction it was built on; its state is mapped back to full DOF space and the reactions come
/// from the full equations.
void run_elimination(const Model& model, const ReducedSystem& reduced, ReducedOde& ode,
                     const ObservedRun& run);

/// Elimination of a nonlinear model by coordinate partitioning with CVODE
/// (dae/formulations/partitioned_ode.hpp): the independent coordinates integrated, the dependent
/// ones solved at every evaluation, a new partition where the dependent block grows
/// ill-conditioned; the reactions from the full equations at each output (the KKT solve of the
/// accelerations). The summary notes the partition and every re-partition. Throws
/// SchemeNotApplicable as PartitionedOde does.
void run_partitioned_elimination(const Model& model, const ObservedRun& run);

}  // namespace condyn
