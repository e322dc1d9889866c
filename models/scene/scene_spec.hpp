#pragma once
/// The parsed, validated scene (scene-format.md): plain data (SolveSpec, the run settings, also
/// checks itself and lists its output times: models/scene/solve_settings.cpp). Produced by
/// parse_scene(); consumed by build_model(). Every field has been checked for type and range;
/// cross-field checks that need the assembled model (ranks, consistency) happen in build_model().

#include <Eigen/Sparse>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/scheme.hpp"
#include "models/core/source_point.hpp"
#include "models/core/time_function.hpp"
#include "models/core/time_table.hpp"

namespace condyn {

/// A matrix or vector read from a Matrix Market file ({ file = "K.mtx" }): held sparse from the
/// file on, never dense.
struct FileMatrix {
  std::string file;  ///< the path as the scene writes it (empty: not given by a file)
  Eigen::SparseMatrix<double> matrix;
  SourcePoint where;  ///< the key, e.g. "model.stiffness.file"
  [[nodiscard]] bool given() const { return !file.empty(); }
  /// Handed over in memory by the Python module, which names it "<array KEY>" (KEY its own key).
  [[nodiscard]] bool in_memory() const { return file.starts_with("<array "); }
  /// Frees the matrix (the file name and key stay, for messages).
  void release() { Eigen::SparseMatrix<double>().swap(matrix); }
};

struct MemberSpec {
  int node_i = 0, node_j = 0;  ///< 1-based node numbers as written in the scene
  double EA = 0.0;             ///< axial stiffness (0 for a rigid member)
  bool rigid = false;  ///< a distance constraint |x_j + u_j − x_i − u_i| = L instead of a bar
  SourcePoint where;
};

struct ModelSpec {
  enum class Type { truss2d, truss3d, matrix, sleigh, andrews, car_axis, pendulum };
  /// Bars: small-displacement (linear stiffness) or exact length change (large displacement).
  enum class Geometry { linear, nonlinear };
  Type type = Type::truss2d;
  // truss2d, truss3d
  int dimension = 2;
  std::vector<std::array<double, 3>> nodes;  ///< z = 0 in 2D
  std::vector<double> masses;
  std::vector<MemberSpec> members;
  Geometry geometry = Geometry::linear;
  std::vector<double> gravity;  ///< empty, or one acceleration component per dimension
  std::vector<int> supports;    ///< 1-based nodes whose every DOF is fixed
  // sleigh
  double body_mass = 0.0, inertia = 0.0, contact_offset = 0.0;
  // matrix
  std::vector<std::string> dofs;
  std::vector<std::vector<double>> mass, stiffness, damping;  ///< damping may be empty
  SourcePoint mass_where, stiffness_where, damping_where;     ///< their keys, when written as rows
  /// The same, given by files instead of rows (models/scene/read_matrix_files.cpp); `dofs` is then
  /// u1..un when the scene omits it.
  FileMatrix mass_file, stiffness_file, damping_file;
  /// damping = { rayleigh = [a0, a1] }: C = a0 M + a1 K (any linear model).
  std::optional<std::array<double, 2>> rayleigh;
  /// What the scene's (frequency, ratio) pairs gave, for the report; empty for [a0, a1].
  std::string rayleigh_rule;
  SourcePoint rayleigh_where;
  /// damping = { modal = z } or { modal = [z1, z2, ...] }: the damping ratio of each mode of the
  /// constrained model, ascending (the last repeats); C built from the modes (models/
  /// modal_damping.cpp). Empty when not given.
  std::vector<double> modal_ratios;
  SourcePoint modal_where;
  SourcePoint where;
};

struct LoadSpec {
  std::string dof;     ///< empty when `pattern` is given
  FileMatrix pattern;  ///< pattern = { file = "f.mtx" } (n x 1): the load is pattern x value(t)
  TimeFunction value;
  SourcePoint where;
};

/// The line of the k-th of a key's values (`lines` from TomlAccess::dof_values), else `fallback`
/// (a scene from a dict has no lines).
[[nodiscard]] inline int line_of(const std::vector<int>& lines, std::size_t k, int fallback) {
  return k < lines.size() && lines[k] > 0 ? lines[k] : fallback;
}

struct ConstraintSpec {
  enum class Level { position, velocity };
  std::string name;
  std::vector<std::pair<std::string, double>> terms;  ///< in the order written
  std::vector<int> term_lines;                        ///< each term's line
  Level level = Level::position;
  TimeFunction value;
  SourcePoint where;
};

/// [[constraint_block]]: m position-level rows A u = scale(t) g at once, named PREFIX1..PREFIXm.
struct ConstraintBlockSpec {
  std::string prefix;  ///< name = "PREFIX" (default block1_, block2_, ...)
  FileMatrix A;        ///< m x n
  FileMatrix g;        ///< m x 1 (not given: 0)
  TimeFunction scale = TimeFunction::constant(1.0);
  SourcePoint where;
};

/// [ground_motion] (scene-format.md, "Ground motion"): the ground accelerates by a_g(t) along the
/// influence vector r; in coordinates relative to the ground the equations gain the load
/// −M r a_g(t), and every output (displacement, velocity) is relative to the ground.
struct GroundMotionSpec {
  TimeFunction acceleration;  ///< a_g(t)
  int direction = -1;         ///< truss: r = 1 on every node's x (0), y (1) or z (2) DOF
  std::vector<std::pair<std::string, double>> influence;  ///< matrix model: r by DOF name
  std::vector<int> influence_lines;                       ///< each entry's line
  SourcePoint where;
};

struct InitialSpec {
  std::vector<std::pair<std::string, double>> displacement, velocity;
  std::vector<int> displacement_lines, velocity_lines;  ///< each entry's line
  /// Project (u0, v0) onto the constraints (minimum-norm Gauss-Newton) instead of refusing an
  /// inconsistent start.
  bool project = false;
  /// [initial] static: u(0) is the constrained static equilibrium at t = 0 (linear models).
  bool static_start = false;
  SourcePoint where;  ///< of the [initial] table; its path is empty when there is none
  /// Whether the scene has an [initial] table (from a file or a Python dict, whose nodes have
  /// no line: testing the line sent a dict scene's start errors to other keys).
  [[nodiscard]] bool given() const { return !where.path.empty(); }
};

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
  /// [solve] max_order: the highest BDF order (1 to 5, default 5). BDF2 damps the stiff modes a
  /// step does not resolve (its amplification tends to 0 as h ω grows), BDF3 to 5 much less.
  int max_order = 5;
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

enum class Quantity {
  displacement,
  velocity,
  acceleration,
  absolute_acceleration,  ///< u'' + r a_g(t) under [ground_motion] (columns acc_abs_<dof>)
  reaction,
  multiplier,
  drift,
  energy
};

/// The columns of the `energy` quantity, in order (docs/energy.md): T + V, the balance's error,
/// T, V, the energy dissipated, the work of the loads and of the constraint forces.
inline constexpr std::array<std::string_view, 7> kEnergyColumns = {
    "energy",     "energy_error",    "energy_kinetic", "energy_potential", "energy_dissipated",
    "work_loads", "work_constraints"};

struct OutputSpec {
  std::vector<Quantity> quantities = {Quantity::displacement, Quantity::drift};
  std::vector<int> quantities_lines;  ///< the line of each `quantities` entry (0: not from a file)
  std::string file;                   ///< empty: decided by the CLI
  int file_line = 0;                  ///< the line of `file` (0: not from a file)
  /// [output] dofs: the DOFs that get displacement, velocity, acceleration and reaction columns, as
  /// names or patterns where `*` stands for any run of characters; empty: every DOF.
  std::vector<std::string> dofs;
  std::vector<int> dofs_lines;  ///< the line of each `dofs` entry (0: not from a file)
  SourcePoint where;
};

/// The DOF indices (ascending) the output's `dofs` patterns select among `names`; every DOF when
/// there are no patterns.
[[nodiscard]] std::vector<int> selected_dofs(const OutputSpec& output,
                                             const std::vector<std::string>& names);
/// Whether `name` matches `pattern`, where `*` stands for any run of characters (none included).
[[nodiscard]] bool matches_dof_pattern(const std::string& pattern, const std::string& name);

/// [[check]] (scene-format.md, "Checks for a user's own validation suite"): what a run of the scene
/// must satisfy, evaluated by `condyn check` (validation/studies/user_checks.hpp). `quantity` is a
/// CSV column name; which column it is (a DOF's displacement, a reaction, ...) is resolved against
/// the built model.
struct CheckSpec {
  enum class Form {
    at_value,   ///< |computed(at) − value| <= tolerance, `at` an output time
    max_abs,    ///< max over output times of |computed| <= bound
    reference,  ///< max over the reference's rows of |computed − reference| <= tolerance
  };
  std::string quantity;
  Form form = Form::max_abs;
  double at = 0.0, value = 0.0, tolerance = 0.0, bound = 0.0;
  std::shared_ptr<const TimeTable> reference;  ///< the reference's samples of `quantity`
  SourcePoint where;                           ///< "check[2]" and its line
};

struct SceneSpec {
  std::string file;  ///< path the scene was read from (or "<embedded:NAME>")
  std::string name;
  /// `units = "SI"` (metres, kilograms, seconds): g is then 9.80665 in the scene's units, so
  /// ground motion peaks are also given in g and judged against it
  /// (models/assembly/ground_records.hpp). Unset: any consistent units (the contract), g unknown.
  bool si_units = false;
  ModelSpec model;
  std::vector<LoadSpec> loads;
  std::vector<ConstraintSpec> constraints;
  std::vector<ConstraintBlockSpec> constraint_blocks;  ///< rows after `constraints`
  std::optional<GroundMotionSpec> ground_motion;
  InitialSpec initial;
  SolveSpec solve;
  OutputSpec output;
  std::vector<CheckSpec> checks;
  /// Every file the scene names and the reader read (Matrix Market matrices, tables, check
  /// references), as opened (relative to the scene's folder): outputs must not replace them.
  std::vector<std::string> input_files;
};

[[nodiscard]] const char* to_string(Quantity q);

}  // namespace condyn
