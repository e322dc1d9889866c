#pragma once
/// Options in, summary out: what the integrator is asked to do and what it did.

#include <Eigen/Dense>
#include <chrono>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "dae/interface/singular_passage.hpp"
#include "dae/interface/unknown_kind.hpp"

namespace condyn {

struct TrajectoryRow;  // dae/run/trajectory.hpp

/// Where a long run stands, for a progress line (IntegratorOptions::on_progress).
struct Progress {
  double t0 = 0.0, t = 0.0, t_end = 0.0;  ///< start, time reached, end of the run
  long steps = 0;                         ///< internal steps so far
  double elapsed_seconds = 0.0;           ///< wall time since the loop started
};

/// What the integrator is asked to do, in numbers only: tolerances per kind of unknown, first
/// step, output times, load steps, budgets (a run plan holds these: dae/run/run_plan.hpp).
struct IntegratorSettings {
  double rtol = 1e-8;
  /// Absolute tolerance of the displacements ([solve] atol, in the model's length unit).
  double atol = 1e-10;
  /// Absolute tolerances of the other kinds of unknown ([solve] atol_velocity, atol_multiplier,
  /// atol_mu); unset means atol (plan() sets them from the model's scales).
  std::optional<double> atol_velocity, atol_multiplier, atol_mu;
  /// The model's time scale T (dae/formulations/model_scales.hpp): higher-index components' Newton
  /// weights are scaled by (h/T)^(k−1), a pure number. 1 when the caller knows no model.
  double time_scale = 1.0;
  /// First step of the higher-index schemes (GGL, index2, index3), at most half the first output
  /// interval; unset: 1e-8 of that interval.
  std::optional<double> first_step;
  /// The first sample time of a tabulated load or right-hand side after t0 (infinity: none).
  /// Every scheme's first step stays below half of it: with no history, IDA's error test could
  /// not shrink a first step across a ramp of 1e-9 s at t = 0 (ten failures from 5e-4).
  double first_kink = std::numeric_limits<double>::infinity();
  bool dense_linear_solver = false;  ///< SUNDIALS dense LU instead of KLU (tiny systems only)
  int max_order = 5;                 ///< the highest BDF order the integrator may use (1 to 5)
  /// Singular configurations of a nonlinear model bridged by generalized-α steps
  /// (dae/integrators/passage_bridge.hpp; [solve] bridge_singular).
  bool bridge_singular = true;
  /// The problem's own condensed Newton solve (DaeProblem::newton_system), when it has one and
  /// KLU is used ([solve] newton = "condensed").
  bool condensed_newton = false;
  /// That condensed Newton matrix factored by CHOLMOD instead of KLU (symmetric positive definite:
  /// dae/run/factorization_choice.hpp); implies condensed_newton.
  bool cholmod = false;
  /// The ordering CHOLMOD analyses that matrix under: the least fill that the plan's analysis
  /// found (dae/run/factorization_choice.hpp), so that it is not analysed again under every one.
  std::string cholmod_ordering;
  /// Whether atol_multiplier and atol_mu, which hold for rows of the largest coefficient, are
  /// raised for rows more than kRowScaleSpan smaller (DaeProblem::multiplier_row_scales) by the
  /// factor they lie beyond it: a multiplier is a force per unit coefficient, so a row written
  /// 1e9 times smaller has a multiplier 1e9 times larger, and one tolerance for all asked
  /// roundoff of the small rows' (GGL failed on rows of 2e9 and 1 at rtol 1e-10). Set for
  /// tolerances derived from the model, not for those a scene gives.
  bool multiplier_atol_per_row = false, mu_atol_per_row = false;
  /// Rows of coefficients within this factor of the largest share its tolerance; so do rows whose
  /// lightest mass lies within it of multiplier_mass.
  static constexpr double kRowScaleSpan = 1e3;
  /// The mass m the common atol_multiplier was derived with (ModelScales::mass; 0: none). With
  /// multiplier_atol_per_row, a row whose lightest mass m_i is more than kRowScaleSpan below it
  /// gets atol_multiplier times m_i kRowScaleSpan / m: a force error Δλ moves that mass by
  /// Δλ T²/m_i, and with the mean mass a 1e-6 kg tip on a 1e6 kg body had its rod's λ (1e-5 N)
  /// below its atol (4.9e-4).
  double multiplier_mass = 0.0;
  std::vector<double> output_times;    ///< ascending, first one is the initial time
  std::vector<double> breakpoints;     ///< load steps inside (t0, t_end): stop and restart there
  long max_steps_per_output = 100000;  ///< between two output times; more is a failure
  long max_steps = 0;                  ///< over the whole run (0: no limit); more is a failure
  double max_wall_seconds = 0.0;       ///< wall time of the loop (0: no limit); more is a failure
  /// IntegratorOptions::on_progress is called after this much wall time, then every
  /// progress_every_seconds.
  double progress_after_seconds = 2.0;
  double progress_every_seconds = 2.0;
  /// Throws std::invalid_argument naming the bad field.
  void validate() const;
  /// The absolute tolerance of one kind of unknown.
  [[nodiscard]] double atol_of(UnknownKind kind) const;
  /// One absolute tolerance per unknown (`kinds` empty: atol for all `size` unknowns).
  /// `row_scales`: per unknown, the largest |coefficient| of its constraint row for multipliers
  /// and μ (0 for other unknowns, empty for none), which the per-row flags above apply.
  /// `row_masses`: per unknown, the lightest mass of a multiplier's row (DaeProblem::
  /// multiplier_row_masses; 0 for other unknowns, empty for none), applied with multiplier_mass.
  [[nodiscard]] Eigen::VectorXd atol_vector(const std::vector<UnknownKind>& kinds, int size,
                                            const Eigen::VectorXd& row_scales = {},
                                            const Eigen::VectorXd& row_masses = {}) const;
};

/// The settings and what the caller observes of the run: the callbacks and the outputs a run
/// computes only when asked (execute() adds them to a plan's settings).
struct IntegratorOptions : IntegratorSettings {
  /// Called from the loop once a run has taken progress_after_seconds of wall time, then every
  /// progress_every_seconds (dae/ never prints: the caller decides what to show).
  std::function<void(const Progress&)> on_progress;
  /// Called after every internal step with the step's exact t and y (not interpolated).
  std::function<void(double t, const Eigen::VectorXd& y)> on_step;
  /// Where the run watches for singular configurations (dae/run/singular_passages.hpp): the
  /// constraint rows' conditioning at (t, y), y in the problem's layout, as the run's monitor
  /// computes it. A bridge (dae/integrators/passage_bridge.hpp) asks it at the states on_step
  /// then sees, so each is computed once. Unset otherwise.
  std::function<double(double t, const Eigen::VectorXd& y)> conditioning;
  /// Keep a per-step drift log (Trajectory::steps) for drift plots; off by default.
  bool record_steps = false;
  /// Compute accelerations at the output rows (Trajectory::acceleration, TrajectoryRow::
  /// acceleration; dae/formulations/acceleration.hpp); off by default: a run pays only for what it
  /// outputs.
  bool accelerations = false;
  /// The multiplier schemes' λ at output rows from the constraints at acceleration level
  /// (dae/formulations/row_multipliers.hpp) rather than their own unknowns: one solve per row, for
  /// runs whose reactions, multipliers or accelerations are used.
  bool row_multipliers = true;
  /// When set, every output row (t, y, y') goes here as it is computed instead of into the
  /// returned RawTrajectory, which then holds the times only (results streamed, nothing of size
  /// unknowns x output times held).
  /// `integrals`: the integrals of `integrand` from the first output time to t (empty without one).
  std::function<void(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                     const Eigen::VectorXd& integrals)>
      on_output;
  /// When set, the loop integrates this function of (t, y, y') over the run, `integrand_size`
  /// components, by three-point Gauss-Legendre quadrature on the integrator's interpolant in every
  /// internal step (exact for polynomials of degree 5 in t), and reports the integrals at each
  /// output (RawTrajectory::integrals, on_output). The energy balance's work terms use it.
  std::function<Eigen::VectorXd(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp)>
      integrand;
  int integrand_size = 0;
  /// When set with `integrand`: what the integrals gain at a load step at t, where the state may
  /// jump from y_before to y_after (a massless DOF held by stiffness goes to its new equilibrium
  /// at once, and the load does work over that jump that no step's quadrature sees).
  std::function<Eigen::VectorXd(double t, const Eigen::VectorXd& y_before,
                                const Eigen::VectorXd& y_after)>
      integrand_jump;
  /// Compute the energy balance at the output rows (TrajectoryRow::balance; docs/energy.md).
  bool energy_balance = false;
  /// Set by execute() from RunHooks::on_row: the observed run streams full-space rows there (and
  /// sets on_output itself).
  std::function<void(const TrajectoryRow&)> on_row;
};

/// One remark on a run: what it is about, and its text.
struct RunNote {
  enum class Kind {
    integrator,      ///< the integrator's (projections made, error weights floored, nothing to do)
    scheme_setting,  ///< the scheme's parameters (Baumgarte's gains, penalty's weights)
    treatment,       ///< the mixed treatment's rows eliminated and kept
    fallback,        ///< auto's elimination refused, GGL instead
    order_cap,       ///< [solve] max_order below 5, and the highest order used
    warning,         ///< a result to doubt (error tests, atol, drift)
    singular_passage,  ///< passages near a singular configuration
  };
  Kind kind = Kind::integrator;
  std::string text;
  bool operator==(const RunNote&) const = default;
};

struct SolveSummary {
  std::string scheme;
  long steps = 0;
  long residual_evals = 0;
  long jacobian_evals = 0;
  long newton_iterations = 0;
  long newton_failures = 0;
  long error_test_failures = 0;
  long restarts = 0;       ///< re-initialisations at load steps
  int max_order_used = 0;  ///< the highest BDF order any step used
  double last_step = 0.0;
  double wall_seconds = 0.0;
  double max_drift_position = 0.0;
  double max_drift_velocity = 0.0;
  /// max over the run and the position-level rows of |φ_i| / s_i, s_i the row's largest
  /// coefficient at t = 0 (ConstraintDrift::relative_position): a length in the model's unit.
  double max_relative_drift_position = 0.0;
  /// A mechanism's joint where max_relative_drift_position was reached (its rows are named
  /// "<joint>.<what>"); empty for other models, or when nothing drifted.
  std::string worst_drift_joint;
  /// The body whose rigid-body rows (natural coordinates' unit-length and orthogonality rows)
  /// held max_relative_drift_position, when those rows, not a joint's, drifted most; else empty.
  std::string worst_drift_body;
  /// GGL only: max |μ| over the output times (μ vanishes on exact solutions); −1 otherwise.
  double max_abs_mu = -1.0;
  /// max |u| over the output rows (those before a failure included).
  double max_abs_displacement = 0.0;
  /// Remarks on the run in the order printed (brief(), notes_text()): what the scheme was set up
  /// with, what the integrator did of note, warnings.
  std::vector<RunNote> notes;
  /// The notes as one line, joined by "; " (what `condyn run` prints and Python's "notes"),
  /// without those in `said_before` (warnings a caller printed before the run).
  [[nodiscard]] std::string notes_text(const std::vector<RunNote>& said_before = {}) const;
  /// Appends a note of `kind`.
  void add_note(RunNote::Kind kind, std::string text);
  /// Passages near a singular configuration (models whose constraint Jacobian depends on the
  /// state; dae/run/singular_passages.hpp), in time order.
  std::vector<SingularPassage> singular_passages;
  /// A warning when at least half of 10,000 or more steps failed the error test, which no normal
  /// run does (the scenes of models/ and validation/ fail a small fraction of their steps): a
  /// run trapped that way (a conical pendulum in steady rotation under GGL) can end far off
  /// with exit 0 (docs/limitations.md; figures in docs/benchmarks.md).
  [[nodiscard]] std::optional<std::string> error_test_warning() const;
  /// A warning when `atol` exceeds the largest displacement of a run that moved: the error
  /// test then holds none of the motion (an SI oscillator peaking at 2 mm, run at atol 10, ends
  /// wrong by its own size under every scheme, with exit 0).
  [[nodiscard]] std::optional<std::string> atol_warning(double atol) const;
  /// How far beyond the error test's own tolerance a drift may grow before it is warned of.
  static constexpr double kDriftMultiple = 100.0;
  /// A warning when the position drift relative to each row's scale exceeds kDriftMultiple
  /// (rtol max|u| + atol), the displacement error the error test allows: the constraints are
  /// then held to far less than the tolerance asked (index1's pendulum grows visibly longer over
  /// a long run, with exit 0). `condyn check` fails on it.
  [[nodiscard]] std::optional<std::string> drift_warning(double rtol, double atol) const;
  int unknowns = 0;
  long jacobian_nonzeros = 0;
  std::string termination = "not run";
  /// termination for a run that reached `t`: "reached t = 2.000000" as it has always read where
  /// six decimals give t exactly, t's shortest form otherwise ("reached t = 1e-10", not 0.000000).
  void set_reached(double t);
  /// One line for the terminal; its notes without those in `said_before`.
  [[nodiscard]] std::string brief(const std::vector<RunNote>& said_before = {}) const;
  /// Where the worst drift was: "joint hinge", "the rigid-body rows of body rod1", or "".
  [[nodiscard]] std::string worst_drift_place() const;
};

/// Sets `summary.wall_seconds` to the time since its construction when it goes out of scope: on
/// every exit of an integration, a failed one's too (a failed run reported 0 s).
class WallTimer {
 public:
  explicit WallTimer(SolveSummary& summary)
      : summary_(summary), start_(std::chrono::steady_clock::now()) {}
  ~WallTimer() {
    summary_.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  WallTimer(const WallTimer&) = delete;
  WallTimer& operator=(const WallTimer&) = delete;

 private:
  SolveSummary& summary_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace condyn
