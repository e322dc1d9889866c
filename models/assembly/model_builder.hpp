#pragma once
// Internal to build_model(): the state the stages of turning a SceneSpec into a Model share, and
// the stages themselves, each defined in the file named above its group. The order in which
// build_model() calls them, and why, is written down in models/assembly/build_model.cpp.

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "models/assembly/build_model.hpp"
#include "models/core/constraint_groups.hpp"
#include "models/core/linear_system.hpp"
#include "models/core/model.hpp"
#include "models/core/time_function.hpp"
#include "models/scene/scene_spec.hpp"
#include "models/systems/point_mass_system.hpp"

namespace condyn {

class InconsistentGivenValues;

// Relative size below which a (row-normalised) constraint set counts as rank deficient.
// Rows are scaled to unit norm first, so this compares directions: 1e-10 keeps constraints whose
// normals differ by more than ~1e-10 rad, far below anything a scene means on purpose.
constexpr double kRankTolerance = 1e-10;
// [initial] project and the mass and slave checks still factor dense matrices (constraints x DOFs):
// refuse or skip sizes whose memory and time would look like a hang (4e6 doubles = 32 MB, and
// seconds of dense QR).
constexpr double kMaxDenseEntries = 4e6;
// A connected group of constraints up to this many constraint-DOF pairs is rank-checked by a
// dense column-pivoted QR (at most 80 KB and ~1e6 flops per row of the group, so linear in the
// rows), larger groups by SuiteSparseQR: small scenes keep the dense QR's exact decisions.
constexpr double kDenseBlockEntries = 1e4;

// input_checks.cpp
std::string fmt(double v);
/// A figure computed from the scene (a residual, a norm) for a message: fmt(v), or, when it is
/// not finite, "not a number (CAUSE overflow the double range)" or "infinite (...)": a message
/// never shows "nan" or "-nan", and says what overflowed.
std::string computed_fmt(double v, const std::string& cause);
double magnitude_bound(const TimeTerm& term, int order, double t_end);
double magnitude_bound(const TimeFunction& f, double t_end);
bool all_finite(const Eigen::SparseMatrix<double>& m);
// multibody_model.cpp
/// The model's size of the contract: the largest distance between two named points at t = 0
/// (ground's included), 1 when there is one point (docs/scenes.md).
double mechanism_size(const Mechanism& m);

class ModelBuilder {
 public:
  ModelBuilder(const SceneSpec& spec, BuildReport& report) : spec_(spec), report_(report) {}

  /// The stages in their order: models/assembly/build_model.cpp.
  Model build();

  /// An evaluator of the model as built so far: its nonlinear system, or the linear system of its
  /// matrices and rows (the Model's own LinearSystem is made last, from the final model).
  [[nodiscard]] std::unique_ptr<MechanicalSystem> evaluator() const {
    if (model_.nonlinear) return model_.evaluator();
    return std::make_unique<LinearSystem>(model_);
  }

  // dofs_and_loads.cpp
  [[noreturn]] void fail(const SourcePoint& where, const std::string& problem) const;
  int dof(const std::string& name, const SourcePoint& where) const;
  void set_dofs(std::vector<std::string> names);
  void build_loads();
  void add_pattern_load(const LoadSpec& l, const TimeFunction& value, double bound,
                        std::vector<double>& total);
  // ground_motion.cpp
  void add_ground_motion(std::vector<double>& total);
  // influence_vector.cpp
  [[nodiscard]] Eigen::VectorXd influence_vector() const;
  // ground_records.cpp
  void report_ground_records(const TimeFunction& acceleration);

  // input_checks.cpp
  /// Refuses a time function that overflows on [0, t_end], and a displacement record unless
  /// `prescribed_displacement` (a position-level right-hand side: a load needs a force).
  void check_time_function(const TimeFunction& f, const SourcePoint& where,
                           bool prescribed_displacement = false) const;
  /// A load's, ground motion's or constraint's time function as the run sees it: steps after
  /// t_end left out, with a warning naming `where`; a warning too for a table that ends before
  /// t_end on a nonzero value, which the contract holds from there on (a record cut short).
  TimeFunction acting_in_run(const TimeFunction& f, const SourcePoint& where);
  void check_finite() const;
  void check_magnitudes();
  /// Warns of an rtol above 1e-2 (fewer than two correct digits), wherever it was set: the
  /// scene, `--rtol` or Python's rtol.
  void check_tolerance();
  void check_size();
  void check_degenerate_dofs() const;
  [[nodiscard]] SourcePoint quantity_key(Quantity q) const;
  /// Refuses DOF `name`: nothing in the system acts on it, so its motion is undefined.
  [[noreturn]] void fail_undefined_motion(const std::string& name) const;

  // truss_assembly.cpp
  void build_truss();

  // matrix_model.cpp
  Eigen::SparseMatrix<double> sparse_psd(const std::vector<std::vector<double>>& rows,
                                         const std::string& key, const SourcePoint& where) const;
  Eigen::SparseMatrix<double> file_psd(const FileMatrix& m, const std::string& key) const;
  void check_sparse_inertia(const FileMatrix& m, const std::string& key) const;
  void check_psd(const Eigen::MatrixXd& dense, const SourcePoint& where,
                 const std::string& file = "") const;
  void check_unreached_dofs() const;
  void build_matrix();
  void apply_rayleigh();
  /// Rayleigh damping of a truss with rigid members or large displacements (its system's).
  void rayleigh_on_members(double a0, double a1);
  void apply_modal_damping();   // modal_damping.cpp
  void apply_rayleigh_modes();  // modal_damping.cpp
  /// ω of the two modes damping.rayleigh.modes names, sparse beyond the dense limit.
  [[nodiscard]] std::array<double, 2> rayleigh_mode_frequencies() const;  // modal_damping.cpp

  // nonlinear_systems.cpp
  void build_benchmark();
  void build_sleigh();
  void finish_sleigh();
  void finish_point_masses();
  void keep_reference_only_at_published_start();
  void linearize();

  // multibody_model.cpp
  void build_mechanism();
  void report_joints();
  // multibody_start.cpp
  [[nodiscard]] Eigen::VectorXd mechanism_row_gradients(double size) const;
  [[nodiscard]] double mechanism_speed(double size) const;
  void check_mechanism_start() const;
  [[nodiscard]] std::string mechanism_projection_report(const Eigen::VectorXd& u_in,
                                                        const Eigen::VectorXd& v_in) const;
  void project_mechanism();

  // constraint_rows.cpp
  void check_coefficients(const ConstraintSpec& cs) const;
  void refuse_table_rhs(const TimeFunction& f, const SourcePoint& where, bool velocity_level) const;
  void check_record_rhs(const TimeFunction& f, const SourcePoint& where, bool velocity_level) const;
  void build_constraints();
  // constraint_blocks.cpp
  void append_constraint_blocks(std::vector<Eigen::Triplet<double>>& trip);

  // rank_check.cpp
  /// A redundant constraint (a combination of others, right-hand sides compatible) that the scene
  /// asks to drop.
  struct Dependent {
    int row = 0;
    std::string others;  ///< the constraints it combines, quoted
  };
  void drop_constraint(const Dependent& d);
  [[nodiscard]] std::optional<Dependent> check_rank() const;
  /// Whether the dependent rows `combo` of a nonlinear model (weights of the normalised rows,
  /// rows of `group`) stay dependent at second order along the motions the rows allow at t = 0:
  /// redundant, or only singular there. Refuses them when they are not (naming them).
  void check_redundant_at_second_order(const std::vector<std::pair<int, double>>& combo,
                                       const std::vector<double>& row_norm,
                                       const ConstraintGroup& group, const std::string& names,
                                       const std::string& rank_text) const;
  /// A nonlinear model that dropped rows integrates the others only: its system becomes a
  /// RowSubsetSystem of the kept rows.
  void keep_independent_rows();
  /// The row of the model's system that constraint j is (the same until rows of a nonlinear model
  /// are dropped, and again once keep_independent_rows has wrapped its system).
  [[nodiscard]] int system_row(int j) const {
    return kept_rows_.empty() ? j : kept_rows_[static_cast<std::size_t>(j)];
  }

  // initial_state.cpp
  void build_initial();
  void check_initial_consistency() const;
  void settle_initial_roundoff();
  void check_nonlinear_consistency() const;
  /// Refuses the first of constraints `rows` that (u0, v0) violate (nonlinear models).
  void check_nonlinear_rows(const std::vector<int>& rows) const;
  [[noreturn]] void refuse_given_values(const InconsistentGivenValues& e) const;
  void project_initial();
  // static_start.cpp
  void solve_static_initial();

  // mass_regularity.cpp
  void check_massless_dofs();
  void report_massless_dofs(const std::vector<bool>& held);
  void warn_given_held_values(const std::vector<bool>& held);
  [[nodiscard]] std::vector<bool> held_massless() const;
  void check_singular_mass(const std::vector<bool>& held);

  // solve_settings_checks.cpp
  void check_energy_output() const;
  void check_absolute_acceleration() const;
  void check_output() const;
  void check_output_dofs() const;
  void check_output_points() const;
  void check_slaves() const;
  // derived_columns.cpp
  void build_derived();

 private:
  const SceneSpec& spec_;
  BuildReport& report_;
  Model model_;
  PointMassLayout layout_;
  bool nonlinear_truss_ = false;
  std::vector<SourcePoint> rod_where_;
  Eigen::VectorXd base_u0_, base_v0_;  ///< built-in models' published initial state
  /// A nonlinear model's rows left after drops, in its system's numbering (empty: none dropped,
  /// or the system already restricted to them).
  std::vector<int> kept_rows_;
  /// A mechanism's rows: the joint of each (−1: a body's rigid row), and which depend on t.
  std::vector<int> row_joint_;
  std::vector<bool> row_rheonomic_;
  /// A mechanism's rows that redundant = "drop" removed: (joint, row name), in the order dropped.
  std::vector<std::pair<int, std::string>> dropped_joint_rows_;
};

}  // namespace condyn
