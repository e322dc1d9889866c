#pragma once
/// The constant model built from a validated scene:
///
///   M u'' + C u' + K u = f(t),   A u = g(t)  (position level),   A_v u' = h(t)  (velocity level)
///
/// with sparse M, C, K (n x n), loads f(t) = sum_k b_k load_k(t) (b_k = e_dof(k) or a pattern),
/// and the constraint matrix A (m x n) holding every constraint row in scene order. Nothing in a
/// Model changes after build_model(): state and scratch space live in the formulations and solvers.

#include <Eigen/Sparse>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/benchmark_model.hpp"
#include "models/core/constraint_level.hpp"
#include "models/core/derived_column.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/output_map.hpp"
#include "models/core/rayleigh.hpp"
#include "models/core/shared_sparse.hpp"
#include "models/core/source_point.hpp"
#include "models/core/time_function.hpp"

namespace condyn {

/// f(t) += e_dof value(t), or pattern value(t) for a [[load]] pattern (one sparse vector, however
/// many DOFs it loads: linear in its nonzeros wherever the loads are used).
struct Load {
  int dof = 0;  ///< the loaded DOF; -1 for a pattern load
  TimeFunction value;
  Eigen::SparseVector<double> pattern;  ///< n entries for a pattern load, else empty

  /// f += s e_dof (or s pattern).
  void add_to(Eigen::Ref<Eigen::VectorXd> f, double s) const {
    if (dof >= 0) {
      f[dof] += s;
    } else {
      for (Eigen::SparseVector<double>::InnerIterator it(pattern); it; ++it)
        f[it.index()] += s * it.value();
    }
  }
  /// e_dofᵀ u (or patternᵀ u).
  [[nodiscard]] double dot(const Eigen::Ref<const Eigen::VectorXd>& u) const {
    if (dof >= 0) return u[dof];
    double sum = 0.0;
    for (Eigen::SparseVector<double>::InnerIterator it(pattern); it; ++it)
      sum += it.value() * u[it.index()];
    return sum;
  }
};

/// The loads' share of an energy balance at (t, u, v): the constant ones (gravity) as a
/// potential, −f·u, added to `potential`; the time-dependent ones as power, f(t)·v (steps on as
/// `steps` says, TimeFunction::derivative), added to `power`.
void add_load_energy(const std::vector<Load>& loads, double t, double steps,
                     const Eigen::Ref<const Eigen::VectorXd>& u,
                     const Eigen::Ref<const Eigen::VectorXd>& v, double& potential, double& power);

struct Constraint {
  std::string name;
  ConstraintLevel level = ConstraintLevel::position;
  std::vector<std::pair<int, double>> coefficients;  ///< (dof index, a_i), dof ascending
  TimeFunction value;                                ///< right-hand side as written: g(t) or h(t)
  /// Position-level right-hand side. For a position constraint, `value`. For a velocity
  /// constraint (linear, constant coefficients, hence integrable: §5.5.3, eq. 5.14) it is
  /// a·u(0) + integral_0^t h: the chapter's integration with the constants fixed by u(0).
  TimeFunction position_value;
  /// Rows of nonlinear models that are not linear (coefficients empty): what the row says, e.g.
  /// "distance |x3 − x2| = 5" or "no sideways slip at the contact point (knife edge)".
  std::string nonlinear_kind;
  bool nonholonomic = false;  ///< a velocity row that integrates to no position constraint
  SourcePoint where;
};

struct Model {
  std::string file, name;
  std::vector<std::string> dof_names;
  /// The DOF indices sorted by name, for find_dof's binary search (index_dofs() sets it): 4 bytes
  /// a DOF where a std::map<std::string, int> takes about 70 (issue 12).
  std::vector<int> dof_order;
  Eigen::SparseMatrix<double> M, C;  ///< C has no nonzeros when the scene has no damping
  /// The stiffness, held once for the model and its LinearSystem (read *K, write K.edit()).
  SharedSparse K;
  std::vector<Load> loads;
  /// [ground_motion]: the influence vector r and the ground's acceleration a_g(t) (the load
  /// −M r a_g is among `loads`); the outputs are relative to the ground.
  struct Ground {
    Eigen::VectorXd r;
    TimeFunction acceleration;
  };
  std::optional<Ground> ground;
  std::vector<Constraint> constraints;
  /// The time functions a mechanism's drives prescribe (its system evaluates them; no
  /// constraint's `value` holds them): their tables' samples are breakpoints.
  std::vector<TimeFunction> drives;
  /// Names of the scene's constraints that [solve] redundant = "drop" removed (no row, no
  /// multiplier column; a check naming one is told why).
  std::vector<std::string> dropped_constraints;
  /// u(0) is the static equilibrium under exact constraints ([initial] static = true): at rest
  /// only where the constraints hold exactly (not under penalty).
  bool static_start = false;
  Eigen::SparseMatrix<double> A;  ///< m x n, row i = constraints[i].coefficients
  /// Set when C is Rayleigh damping a0 M + a1 K and nothing else (no damping matrix or member
  /// dampers beside it): a residual may then form C v from the products with M and K it makes
  /// anyway (dae/formulations/reduced_ode.cpp checks that C still is that).
  std::optional<RayleighCoefficients> rayleigh;
  Eigen::VectorXd u0, v0;
  /// The system every formulation integrates, decided once by the builder: a LinearSystem (owning
  /// copies of M, C, K, A and the loads) for linear models, else the model's own, whose M, f or
  /// constraints depend on the state (large-displacement bars, rigid members, generalized
  /// coordinates, nonholonomic rows); M, C, K and A above then hold its linearization at t = 0
  /// and (u0, v0), for `info`, the rank check and the default gains. A constant prototype: runs
  /// evaluate their own evaluator() (models/core/mechanical_system.hpp), so one model serves many
  /// runs and threads.
  std::shared_ptr<const MechanicalSystem> system;
  bool nonlinear = false;  ///< `system` is not the LinearSystem of M, C, K, A
  /// How results are shown when the columns are not the DOFs (a mechanism: poses, joint
  /// reactions, named points; models/core/output_map.hpp); null: one column per DOF.
  std::shared_ptr<const OutputMap> outputs;
  /// [[derived]] columns, their terms resolved against the columns above (DOFs or `outputs`):
  /// written after every quantity's columns (models/core/derived_column.hpp).
  std::vector<DerivedColumn> derived;
  /// Built-in benchmarks: the published reference state at a time, when one is known there.
  std::function<std::optional<PublishedReference>(double)> reference;
  std::string description;  ///< one line for `condyn info` (built-in models)

  [[nodiscard]] int dofs() const { return static_cast<int>(dof_names.size()); }
  /// Sorts dof_order from dof_names (after they are set).
  void index_dofs();
  /// The index of the DOF called `dof`, if there is one.
  [[nodiscard]] std::optional<int> find_dof(std::string_view dof) const;
  /// The index of the DOF called `dof`; throws std::out_of_range when there is none.
  [[nodiscard]] int dof_at(std::string_view dof) const;
  [[nodiscard]] int constraint_count() const { return static_cast<int>(constraints.size()); }
  [[nodiscard]] bool has_damping() const { return C.nonZeros() > 0; }
  [[nodiscard]] bool is_nonlinear() const { return nonlinear; }
  /// A new evaluator of the system, for one run (or one thread).
  [[nodiscard]] std::unique_ptr<MechanicalSystem> evaluator() const { return system->clone(); }
  /// No damping, time-independent loads (steps at t = 0 included), scleronomic constraints: the
  /// total energy is a first integral. (Nonlinear systems answer through their energy().)
  [[nodiscard]] bool is_conservative() const;

  /// The acceleration in a fixed frame, a + r a_g(t), of a relative acceleration `a` under ground
  /// motion; `a` itself without it.
  [[nodiscard]] Eigen::VectorXd absolute_acceleration(
      double t, const Eigen::Ref<const Eigen::VectorXd>& a) const;
  /// The [[derived]] columns' values at one output row (one per column of `derived`, in order)
  /// from the row's time and vectors (a mechanism's in its output map's columns; `a` empty when
  /// the run computed no accelerations). A column's acc_abs_ terms read `absolute`, the row's
  /// absolute_acceleration(t, a) when the caller has it (the acc_abs_ columns' values), or, when it
  /// is empty, absolute_acceleration(t, a) computed here once for the row. Throws
  /// std::logic_error when a term reads a vector the row lacks (derived_value).
  [[nodiscard]] Eigen::VectorXd derived_values(
      double t, const Eigen::Ref<const Eigen::VectorXd>& u,
      const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
      const Eigen::Ref<const Eigen::VectorXd>& reaction,
      const Eigen::Ref<const Eigen::VectorXd>& absolute) const;
  [[nodiscard]] Eigen::VectorXd derived_values(
      double t, const Eigen::Ref<const Eigen::VectorXd>& u,
      const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
      const Eigen::Ref<const Eigen::VectorXd>& reaction) const {
    return derived_values(t, u, v, a, reaction, Eigen::VectorXd());
  }
  /// Applied loads f(t) (n). Steps are on when start <= step_reference.
  [[nodiscard]] Eigen::VectorXd applied_forces(double t, double step_reference) const;
  [[nodiscard]] Eigen::VectorXd applied_forces(double t) const { return applied_forces(t, t); }
  /// The loads' time derivative of order 1 or 2 at t (a step's is 0; a table's second is 0).
  [[nodiscard]] Eigen::VectorXd applied_forces_derivative(int order, double t) const;
  /// d^order/dt^order of the position-level right-hand sides (m), order in {0, 1, 2}.
  [[nodiscard]] Eigen::VectorXd position_rhs(int order, double t) const;
  /// Times in (0, t_end) where a load step switches on or a drive's table has a sample (kink),
  /// sorted, unique: the integrator stops and restarts there.
  [[nodiscard]] std::vector<double> breakpoints(double t_end) const;
  /// The first sample time after t of a table in a load, ground motion's included (infinity when
  /// none). A ramp of 1e-9 s at t = 0 failed the first step: IDA's first step
  /// (5e-4 there) crossed it and ten error-test failures did not bring it below the ramp.
  [[nodiscard]] double first_kink(double t) const;
};

/// What building a model found worth telling, kept apart from the model (run prints it to the
/// terminal, info to its report; build_model: models/assembly/build_model.hpp).
struct BuildReport {
  /// What [initial] project = true changed, or what static = true solved (empty when neither).
  std::string initial_projection;
  /// Accepted, but worth a look: magnitudes so far from 1, or so spread, that double precision
  /// loses the physics.
  std::vector<std::string> warnings;
  /// What [solve] redundant = "drop" removed, one entry per constraint (empty when nothing).
  std::vector<std::string> dropped_constraints;
  /// The Rayleigh coefficients derived from (frequency, ratio) pairs, when the scene gave pairs.
  std::string damping;
  /// One line per table of [ground_motion] acceleration: its peak over the run and when
  /// (models/assembly/ground_records.hpp).
  std::vector<std::string> ground_records;
  /// The DOFs without mass, counted and the first named, and what holds them ("3 of 12 (ux1,
  /// uy1, u5): 2 in constraints, 1 held by its stiffness ..."); empty when every DOF has mass.
  std::string massless_dofs;
  /// A mechanism's joints, one line each in the chapter's terms: "hinge_O (revolute, ground –
  /// crank): 3 rows hinge_O.x … hinge_O.drive, holonomic, rheonomic (driven)".
  std::vector<std::string> joints;
};

}  // namespace condyn
