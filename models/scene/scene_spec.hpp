#pragma once
/// The parsed, validated scene (scene-format.md): plain data (its run settings, SolveSpec, are
/// models/core/solve_spec.hpp: the solver reads them without the scene format). Produced by
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

#include "models/core/constraint_level.hpp"
#include "models/core/mechanism.hpp"
#include "models/core/node_map.hpp"
#include "models/core/output_quantity.hpp"
#include "models/core/scheme.hpp"
#include "models/core/solve_spec.hpp"
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
  /// `length`: a bar's rest length or a rigid member's length L (> 0); none: the nodes' distance.
  std::optional<double> length;
  /// `c`: an axial dashpot (>= 0) along a bar, force c l' (l' its rate of lengthening).
  double c = 0.0;
  SourcePoint where;
};

struct ModelSpec {
  enum class Type { truss2d, truss3d, matrix, sleigh, andrews, car_axis, pendulum, multibody };
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
  /// matrix: [model] coordinates, the nodes its DOFs move (empty: not given); plot's shapes.
  NodeMap coordinates;
  /// damping = { rayleigh = [a0, a1] }: C = a0 M + a1 K (any linear model).
  std::optional<std::array<double, 2>> rayleigh;
  /// What the scene's (frequency, ratio) pairs gave, for the report; empty for [a0, a1].
  std::string rayleigh_rule;
  SourcePoint rayleigh_where;
  /// damping = { rayleigh = { modes = [i, j], ratios = [z1, z2] } }: a0 and a1 from the
  /// frequencies of modes i and j (1-based) of the constrained model, found by the builder
  /// (models/assembly/modal_damping.cpp); empty otherwise. Where: rayleigh_where.
  std::vector<int> rayleigh_modes;
  std::array<double, 2> rayleigh_mode_ratios{};
  /// damping = { modal = z } or { modal = [z1, z2, ...] }: the damping ratio of each mode of the
  /// constrained model, ascending (the last repeats); C built from the modes (models/
  /// modal_damping.cpp). Empty when not given.
  std::vector<double> modal_ratios;
  SourcePoint modal_where;
  /// multibody: the bodies, joints and force elements ([model], [[body]], [[joint]], [[force]];
  /// models/scene/read_mechanism.cpp), checked against each other.
  std::optional<Mechanism> mechanism;
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
  using Level = ConstraintLevel;  ///< the Model's name for it (models/core/constraint_level.hpp)
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
  /// Matrix model: r by DOF name or `*` pattern (resolved by the builder, whatever the order: a
  /// DOF's own name before any pattern, models/assembly/influence_vector.cpp).
  std::vector<std::pair<std::string, double>> influence;
  std::vector<int> influence_lines;  ///< each entry's line
  FileMatrix influence_file;         ///< matrix model: influence = { file = "r.mtx" } (n x 1)
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
  /// [initial] keep (multibody, with project = true): the values project keeps exactly, as
  /// "body.key" (an output column such as "crank.x", "crank.omega", or a [[body]] key such as
  /// "crank.position", "crank.angular_velocity"), checked against the bodies by the reader.
  std::vector<std::string> keep;
  std::vector<int> keep_lines;  ///< each entry's line (0: not from a file)
  SourcePoint where;            ///< of the [initial] table; its path is empty when there is none
  /// Whether the scene has an [initial] table (from a file or a Python dict, whose nodes have
  /// no line: testing the line sent a dict scene's start errors to other keys).
  [[nodiscard]] bool given() const { return !where.path.empty(); }
};

struct OutputSpec {
  std::vector<Quantity> quantities = {Quantity::displacement, Quantity::drift};
  std::vector<int> quantities_lines;  ///< the line of each `quantities` entry (0: not from a file)
  std::string file;                   ///< empty: decided by the CLI
  int file_line = 0;                  ///< the line of `file` (0: not from a file)
  /// [output] dofs: the DOFs that get displacement, velocity, acceleration and reaction columns, as
  /// names or patterns where `*` stands for any run of characters; empty: every DOF.
  std::vector<std::string> dofs;
  std::vector<int> dofs_lines;  ///< the line of each `dofs` entry (0: not from a file)
  /// [output] points (multibody): markers "body.point" whose global position gets the columns
  /// body.point.x, .y (.z), in the order given.
  std::vector<std::string> points;
  std::vector<int> points_lines;  ///< the line of each `points` entry (0: not from a file)
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

/// [[derived]] (docs/scenes.md, "Derived columns"): the column `name` = Σ coefficient · column
/// over `terms`, each naming a displacement, velocity, acceleration or reaction column of the
/// run, or an earlier [[derived]] column; resolved against the built model
/// (models/assembly/derived_columns.cpp) into Model::derived.
struct DerivedSpec {
  struct Term {
    std::string column;
    double coefficient = 0.0;
    int line = 0;  ///< the term's line (0: not from a file)
  };
  std::string name;
  std::vector<Term> terms;  ///< in the terms table's order (toml++ sorts keys)
  SourcePoint where;        ///< "derived[2]" and the line of its name
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
  std::vector<DerivedSpec> derived;
  /// Every file the scene names and the reader read (Matrix Market matrices, tables, check
  /// references), as opened (relative to the scene's folder): outputs must not replace them.
  std::vector<std::string> input_files;
};

}  // namespace condyn
