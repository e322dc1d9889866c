#pragma once
/// The run settings ([solve] of a scene, or set in code): tolerances, scheme, budgets and the
/// output times. Passed beside the Model to everything that runs it; the scene reader fills them
/// (models/scene/read_solve.cpp), the solver reads them, neither needs the other's headers.

#include <optional>
#include <string>
#include <vector>

#include "models/core/newmark_parameters.hpp"
#include "models/core/scheme.hpp"
#include "models/core/source_point.hpp"

namespace condyn {

/// Relative tolerances accepted ([solve] rtol, --rtol, compare --tolerances): [kMinRtol, 1).
/// Below, a few ulps of 1: no integrator can meet it; 1 and above accept any answer.
inline constexpr double kMinRtol = 1e-15;

/// Absolute tolerances accepted ([solve] atol and atol_*, --atol): at least kMinAtol. The error
/// weights are 1/(rtol |y| + atol): below this they overflow the integrator's error norm (its
/// squares) for any error above 1e-50, and the run fails with nonsense (IDA_ILL_INPUT at a load
/// step with atol 1e-300). No model unit makes such an atol meaningful.
inline constexpr double kMinAtol = 1e-100;

/// The default budget of internal steps between two output times ([solve] max_steps_per_output):
/// a run that crawls at tiny steps (a stiff mode it resolves, a step size near roundoff) fails
/// with its partial result instead of running on unseen, as it would without a step budget.
inline constexpr long kDefaultStepsPerOutput = 100'000;

/// The run settings ([solve]): passed beside the Model to everything that runs it, never stored
/// in it, so one model serves runs at many tolerances and schemes.
struct SolveSpec {
  double t_end = 0.0;
  double output_step = 0.0;
  int output_step_line = 0;  ///< the line of `output_step` (0: not from a file)
  Scheme scheme = Scheme::automatic;
  /// Where the scheme was chosen, for a refusal of it: the scene's `solve.scheme` key and line,
  /// the command line's `--scheme` (line 0), or nothing (the default, or set in code).
  SourcePoint scheme_where;
  double rtol = 1e-8;
  double atol = 1e-10;  ///< displacements (model length unit)
  /// Absolute tolerances of velocities, multipliers and GGL's μ; unset: derived from atol and the
  /// model's scales (dae/formulations/model_scales.hpp).
  std::optional<double> atol_velocity, atol_multiplier, atol_mu;
  std::optional<double> baumgarte_alpha, baumgarte_beta;
  std::optional<double> penalty_weight;  ///< [solve] penalty = { weight = w }
  /// [solve] step (--step): the fixed step of the Newmark family (fixed_step schemes), which
  /// need it; the other schemes choose their steps by rtol and atol and leave it unused (so one
  /// scene serves `compare` under both).
  std::optional<double> step;
  int step_line = 0;  ///< the line of `step` (0: not from a file)
  /// [solve] newmark, hht, generalized_alpha: the Newmark family's parameters.
  NewmarkFamilySpec newmark_family;
  /// [solve] constraints = "mixed" or "multipliers": under a multiplier scheme, eliminate the
  /// constant linear rows whose transform stays sparse and keep multipliers for the rest
  /// (dae/formulations/constraint_treatment.hpp), or keep a multiplier for every row. Unset: mixed
  /// when the scheme is auto, multipliers when a scheme is named (the pure formulations, for
  /// study).
  enum class Treatment { automatic, multipliers, mixed };
  Treatment treatment = Treatment::automatic;
  /// Optional slave DOFs for the master-slave transformation (default: chosen by pivoting).
  std::vector<std::string> slaves;
  std::vector<int> slaves_lines;  ///< the line of each `slaves` entry (0: not from a file)
  /// Dense linear solver instead of KLU (only sensible for tiny systems).
  bool dense_linear_solver = false;
  /// [solve] linear_solver = "auto" (default), "klu" or "cholmod" ("dense" sets
  /// dense_linear_solver): the sparse factorization of the Newton matrices
  /// (dae/run/factorization_choice.hpp). auto: CHOLMOD where the matrix factored is symmetric
  /// positive definite by construction and its predicted factor is smaller than KLU's, else KLU;
  /// cholmod: CHOLMOD, which condenses elimination's Newton systems and is refused where the
  /// Newton matrix is not symmetric positive definite.
  enum class LinearSolver { automatic, klu, cholmod };
  LinearSolver linear_solver = LinearSolver::automatic;
  SourcePoint linear_solver_where;  ///< the `solve.linear_solver` key, for a refusal
  /// [solve] max_order: the highest BDF order (1 to 5, default 5). BDF2 damps the stiff modes a
  /// step does not resolve (its amplification tends to 0 as h ω grows), BDF3 to 5 much less.
  int max_order = 5;
  /// [solve] bridge_singular (default true): the BDF multiplier schemes and projection cross a
  /// nonlinear model's singular configurations by a bridge of generalized-α steps
  /// (dae/integrators/passage_bridge.hpp); false: by their own steps, as the scheme alone does.
  bool bridge_singular = true;
  /// [solve] newton = "full" (default) or "condensed": for linear models under index1, GGL and
  /// elimination, IDA's Newton systems condensed to [u; λ (; μ)]
  /// (dae/linsolve/condensed_newton.hpp) instead of the full Jacobian factored by KLU. Faster, but
  /// not the default: it loses the extreme stiffness and near-redundancy cases of the stress suite
  /// (README, Benchmark).
  bool condensed_newton = false;
  /// [solve] redundant = "drop": remove constraints that are linear combinations of others with
  /// compatible right-hand sides (reported), instead of refusing the scene. Linear models only.
  bool drop_redundant = false;
  /// Budget of the whole run: internal steps (0: none) and wall seconds (0: none); a run that
  /// exhausts either fails with its partial result.
  long max_steps = 0;
  double max_wall_time = 0.0;
  /// [solve] max_steps_per_output: internal steps allowed between two output times (0: the
  /// default, steps_per_output_budget()).
  long max_steps_per_output = 0;
  SourcePoint where;

  /// The budget of steps between two outputs: max_steps_per_output when given, else
  /// kDefaultStepsPerOutput, raised to max_steps when that is larger (a run given a budget of
  /// its own is held to that budget, not to a smaller hidden one).
  [[nodiscard]] long steps_per_output_budget() const;

  /// Throws std::invalid_argument naming the first key out of range (the parser's rules, for
  /// settings made or changed in code).
  void validate() const;
  /// Output times 0, h, 2h, ..., t_end (the last one is t_end even when h does not divide it; a
  /// multiple of h within the time axis' roundoff of t_end is t_end:
  /// models/core/time_roundoff.hpp).
  [[nodiscard]] std::vector<double> output_times() const;
  /// How many output_times() there are, without forming them.
  [[nodiscard]] long output_count() const;
  /// Sets the scheme, as a command line's --scheme does. `constraints` applies to the multiplier
  /// schemes only (a file pairing it with another scheme is refused): under any other it is set
  /// aside, and the returned note says so for the user to see; empty when nothing was set aside.
  /// `chosen_at` names the override for a refusal of the scheme (`--scheme`).
  [[nodiscard]] std::string override_scheme(Scheme s, SourcePoint chosen_at = {});
};

}  // namespace condyn
