#pragma once
/// The scene's section readers (internal to models/): each reads one section of the scene into
/// its part of SceneSpec, through the typed getters of TomlAccess, and is defined in the file
/// named for what it reads. parse_scene_text() (scene_parser.cpp) calls them in order.

#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "models/scene/matrix_market.hpp"
#include "models/scene/scene_spec.hpp"
#include "models/scene/scene_table.hpp"
#include "models/scene/toml_access.hpp"

namespace condyn {

class SceneReader : public TomlAccess {
 public:
  using TomlAccess::TomlAccess;
  /// A reader whose `{ file = NAME }` keys may name matrices in `arrays`
  /// (models/scene/scene_table.hpp).
  SceneReader(std::string file, const ArrayInputs& arrays)
      : TomlAccess(std::move(file)), arrays_(&arrays) {}

  /// The whole scene: its top-level keys, then every section in order (scene_parser.cpp).
  /// What `needs` asks for is checked first.
  [[nodiscard]] SceneSpec read(const toml::table& root, SceneNeeds needs = {}) const;

  /// [model] (read_model.cpp); trusses by read_truss().
  void read_model(const toml::node& node, ModelSpec& model) const;
  void read_truss(const toml::table& t, int dim, ModelSpec& model) const;
  /// The matrix model and Matrix Market files (read_matrix_files.cpp; Rayleigh damping:
  /// read_rayleigh.cpp).
  void read_matrix_model(const toml::table& t, ModelSpec& model) const;
  /// `{ file = "K.mtx" }` at `path`, read (relative to the scene's folder) and held sparse.
  /// `expect`: the size it must declare (checked at its size line, before it is read).
  [[nodiscard]] FileMatrix matrix_file(const toml::node& node, const std::string& path,
                                       const MarketExpectation& expect = {}) const;
  /// The string at `node` (key path `key`) as a file name: not empty, no NUL character
  /// (read_time_function.cpp).
  [[nodiscard]] std::string file_name(const toml::node& node, const std::string& key) const;
  /// The Matrix Market file named by the string `file_node` (key path `key`).
  /// `expect`: as read_matrix_market's (a constraint block's rows need entries, a size known).
  [[nodiscard]] FileMatrix read_market(const toml::node& file_node, const std::string& key,
                                       const MarketExpectation& expect = {}) const;
  /// What a file sized by the matrix model's n DOFs must declare: a load pattern n x 1, a
  /// constraint block n columns; {} (any size) for other models.
  [[nodiscard]] MarketExpectation pattern_size() const;
  [[nodiscard]] MarketExpectation block_size() const;
  /// damping = { rayleigh = [a0, a1] } at `path`.
  void read_rayleigh(const toml::node& node, const std::string& path, ModelSpec& model) const;
  /// rayleigh = { frequencies = [f1, f2], ratios = [z1, z2] } at `path`: a0, a1 derived.
  void read_rayleigh_pairs(const toml::node& node, const std::string& path, ModelSpec& model) const;
  void read_rayleigh_modes(const toml::node& node, const std::string& path, ModelSpec& model) const;
  [[nodiscard]] std::array<double, 2> read_rayleigh_ratios(const toml::table& t,
                                                           const std::string& path) const;
  /// [[constraint_block]].
  void read_constraint_blocks(const toml::node& node, std::vector<ConstraintBlockSpec>& out) const;
  /// [model] type = "multibody" (read_mechanism.cpp): dimension, gravity, the ground's markers.
  void read_mechanism_model(const toml::table& t, ModelSpec& model) const;
  /// [[body]], [[joint]], [[force]] of a multibody model, and the sections it refuses
  /// (read_mechanism.cpp; each table's reader: read_bodies.cpp, read_joints.cpp,
  /// read_forces.cpp).
  void read_mechanism_sections(const toml::table& root, ModelSpec& model) const;
  void read_bodies(const toml::node& node, Mechanism& mechanism) const;
  void read_joints(const toml::node& node, Mechanism& mechanism) const;
  void read_forces(const toml::node& node, Mechanism& mechanism) const;
  /// [initial] keep and [output] points against the mechanism's bodies (read_mechanism_names.cpp).
  void check_mechanism_names(const toml::table& root, const SceneSpec& spec) const;
  /// A mechanism's vector at `node`: `dim` numbers (the third 0 in 2D).
  [[nodiscard]] Mechanism::Vec3 mechanism_vector(const toml::node& node, const std::string& path,
                                                 int dim) const;
  /// `{ NAME = [x, y(, z)], ... }`: a body's or the ground's points, or its axes (`axes`: nonzero
  /// directions, normalized).
  [[nodiscard]] std::vector<Mechanism::Marker> read_markers(const toml::node& node,
                                                            const std::string& path, int dim,
                                                            bool axes) const;
  /// A body's, joint's or marker's name: a CSV-safe name without '.', which joins the names of
  /// columns ("crank.B.x").
  [[nodiscard]] std::string mechanism_name(const toml::node& node, const std::string& path,
                                           const char* what) const;
  /// The body named at `node` (Mechanism::kGround for "ground"), else refused with the nearest
  /// names; `name`, when given, is the name to look up (part of the string at `node`).
  [[nodiscard]] int body_index(const Mechanism& mechanism, const toml::node& node,
                               const std::string& path, const std::string* name = nullptr) const;
  /// The index of the point (axis when `axis`) named at `node` (or `name`) of body `body`, else
  /// refused.
  [[nodiscard]] int marker_index(const Mechanism& mechanism, int body, bool axis,
                                 const toml::node& node, const std::string& path,
                                 const std::string* name = nullptr) const;
  /// [[load]] (read_loads.cpp).
  void read_loads(const toml::node& node, std::vector<LoadSpec>& out) const;
  /// [ground_motion] (read_ground_motion.cpp); the model (read first) decides its keys.
  void read_ground_motion(const toml::node& node, const ModelSpec& model,
                          std::optional<GroundMotionSpec>& out) const;
  /// [model] coordinates of a matrix model (read_coordinates.cpp), after its DOFs.
  void read_coordinates(const toml::node& node, ModelSpec& model) const;
  /// [ground_motion] influence of a matrix model: a file, or DOF names and patterns.
  void read_influence(const toml::node& node, const std::string& path, GroundMotionSpec& g) const;
  /// [[constraint]] (read_constraints.cpp).
  void read_constraints(const toml::node& node, std::vector<ConstraintSpec>& out) const;
  /// [initial] (read_initial.cpp).
  void read_initial(const toml::node& node, InitialSpec& initial) const;
  /// [solve] (read_solve.cpp).
  void read_solve(const toml::node& node, SolveSpec& solve) const;
  /// [solve] step and the Newmark family's parameters (read_newmark.cpp), after the scheme and
  /// t_end.
  void read_fixed_step(const toml::table& t, SolveSpec& solve) const;
  [[nodiscard]] Scheme parse_scheme(const toml::node& node, const std::string& path) const;
  /// [output] (read_output.cpp).
  void read_output(const toml::node& node, OutputSpec& output) const;
  /// [[check]] (read_checks.cpp), after [solve]: `at` must be one of its output times.
  void read_checks(const toml::node& node, const SolveSpec& solve,
                   std::vector<CheckSpec>& out) const;
  /// [[derived]] (read_derived.cpp): names and terms; their columns are resolved by the builder.
  void read_derived(const toml::node& node, std::vector<DerivedSpec>& out) const;

  /// A load's or a constraint's value: a number, one term table or a list of terms
  /// (read_time_function.cpp).
  [[nodiscard]] TimeFunction time_function(const toml::node& node, const std::string& path) const;
  [[nodiscard]] TimeTerm term(const toml::node& node, const std::string& path) const;
  /// `{ type = "displacement_record", … }` at `path` (read_displacement_record.cpp).
  [[nodiscard]] TimeTerm displacement_record(const toml::table& t, const std::string& path) const;
  /// A table's CSV file named by the string `file_node` (key path `key`), relative to the scene's
  /// folder; a bad file is refused naming the key, the file and its line. At least `min_samples`
  /// rows (models/core/time_table.hpp).
  [[nodiscard]] std::shared_ptr<const TimeTable> table_file(const toml::node& file_node,
                                                            const std::string& key,
                                                            const std::string& column,
                                                            std::size_t min_samples = 2) const;

  /// DOF and constraint names, which become CSV column names (scene_names.cpp): check_name()
  /// refuses what would break a CSV field; check_columns() refuses two names that give the same
  /// column under any quantity.
  void check_name(const toml::node& node, const std::string& path, const std::string& name,
                  const char* what) const;
  void check_columns(const toml::table& root, const SceneSpec& spec) const;

 private:
  const ArrayInputs* arrays_ = nullptr;  ///< matrices and tables given in memory (none: files only)
  /// The files read so far (SceneSpec::input_files), noted by the readers of files.
  mutable std::vector<std::string> input_files_;
  /// The matrix model's DOF count once [model] is read (0: not a matrix model, or not yet).
  mutable long long matrix_dofs_ = 0;
  /// The index of a mechanism's body by its name (-1: none), from a table of its names built
  /// once: a search through the bodies for each joint's two made reading a chain quadratic in
  /// its bodies.
  [[nodiscard]] int find_body(const Mechanism& mechanism, const std::string& name) const;
  mutable std::unordered_map<std::string, int> body_at_;  ///< find_body's table
  mutable const Mechanism* body_at_of_ = nullptr;         ///< the mechanism it was built for
};

}  // namespace condyn
