#pragma once
/// The elimination path for nonlinear constraints: coordinate partitioning (Wehage and Haug
/// 1982). The coordinates split into independent ones q_i, which CVODE integrates, and dependent
/// ones u_d, solved from the constraints at every evaluation (dae/formulations/
/// coordinate_partition.hpp). The state is y = [q_i; w_i] (n − m each), and at (t, y):
///
///   positions      φ(t, u) = 0 for u_d, Newton with A_d = ∂φ/∂u_d (sparse LU), warm-started
///                  from the last solution, to newton_tolerance;
///   velocities     A(t, u) u' = −b(t, u) (ψ = A u' + b = 0) for u'_d: A_d u'_d = −ψ(t, u, [w_i;
///   0]); accelerations  the Wehage–Haug reduction  Bᵀ M B q_i'' = Bᵀ (f − M c),  u'' = B q_i'' +
///   c,
///                  B = [I; −A_d⁻¹ A_i], c = [0; A_d⁻¹ γ], whose solution is the independent part
///                  of the KKT system [M Aᵀ; A 0] [u''; λ] = [f; γ] (Bᵀ times its first block row
///                  is the reduction, since A B = 0; its second row is u''_d = A_d⁻¹(γ − A_i
///                  q_i'')). The KKT form is solved (KLU): it stays sparse where Bᵀ M B, A_d⁻¹ A_i
///                  being dense in general, would not, and it gives λ of the full equations with
///                  u''. The KKT matrix's analysis is kept across evaluations (KluByPattern).
///
///   y' = [w_i; q_i''].
///
/// Every constraint row holds to the Newton tolerance at every evaluation, by construction: no
/// drift accumulates. The dependent block can grow singular along a motion (a crank through the
/// position where its dependent coordinate turns): after each accepted step the partition's
/// quality (partition_quality: 1/‖B‖₁, B = [I; −A_d⁻¹ A_i]) is compared with the quality it had
/// when chosen, and below kRepartitionFraction of it a new partition is chosen at that state and
/// the integration restarts there (wants_restart, settle), each one logged.
///
/// A model whose constraints fix every coordinate (a fully driven mechanism: n − m = 0) has an
/// empty state: the loop steps through time without an integrator (integrate_ode), and full()
/// solves the kinematic problem at each time it visits.
///
/// Refuses (SchemeNotApplicable) nonholonomic rows, which have no position form to solve, a
/// Jacobian rank deficient at t0 and a KKT matrix singular at the initial state.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/SparseLU>

#include "dae/formulations/coordinate_partition.hpp"
#include "dae/interface/ode_problem.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "dae/linsolve/kkt.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/model.hpp"

namespace condyn {

class PartitionedOde final : public OdeProblem {
 public:
  /// A re-partition: when, and the coordinates that changed roles.
  struct Repartition {
    double t = 0.0;
    std::vector<int> now_independent, now_dependent;  ///< DOFs that changed roles
    double quality = 0.0;                             ///< of the old partition there
  };

  /// The partition is chosen at (t0, model.u0). Throws SchemeNotApplicable (see above).
  PartitionedOde(const Model& model, double t0);
  PartitionedOde(const PartitionedOde&) = delete;
  PartitionedOde& operator=(const PartitionedOde&) = delete;
  ~PartitionedOde() override;

  /// The Newton iteration's tolerance on the dependent coordinates' last correction (max norm),
  /// floored at the roundoff of the coordinates (kRoundoffUlps ulps of their size).
  void set_newton_tolerance(double tolerance) { tolerance_ = tolerance; }
  [[nodiscard]] double newton_tolerance() const { return tolerance_; }

  [[nodiscard]] int size() const override { return 2 * ni_; }
  void begin_segment(double t0) override { system_->begin_segment(t0); }
  void rhs(double t, ConstRef y, Ref ydot) const override;
  [[nodiscard]] std::vector<UnknownKind> unknown_kinds() const override {
    return condyn::unknown_kinds(ni_);
  }
  [[nodiscard]] bool has_projection() const override { return false; }
  bool project(double /*t*/, ConstRef /*y*/, Ref corr,
               const Eigen::VectorXd& /*settled*/) const override {
    corr.setZero();
    return true;
  }
  void project_error(Ref /*err*/) const override {}
  [[nodiscard]] bool wants_restart(double t, ConstRef y) const override;
  /// Above kDenseJacobianLimit unknowns (or as set_matrix_free says): GMRES on difference-quotient
  /// products instead of the dense Jacobian, whose 2(n − m) columns each cost a right-hand side
  /// (a Newton solve of the positions and a KKT solve) and whose (2(n − m))² entries grow with
  /// the model: a chain of 10⁴ bars would need 3.2 GB and 2·10⁴ evaluations a Jacobian.
  [[nodiscard]] bool matrix_free() const override {
    return matrix_free_.value_or(size() > kDenseJacobianLimit);
  }
  /// Forces the choice of matrix_free() (tests compare both on one model).
  void set_matrix_free(bool on) { matrix_free_ = on; }
  /// The kinematic part of I − γJ, J = [0 I; ∂q''/∂q ∂q''/∂w]: P = [I −γI; 0 I], so
  /// z = [r_q + γ r_w; r_w]. Exact for free motion; GMRES resolves the forces' part, which
  /// γ ∂q''/∂(q, w) keeps near the identity on the steps a non-stiff mechanism takes.
  void precondition(double gamma, ConstRef r, Ref z) const override;
  /// At a restart wants_restart asked for: y re-expressed in the new partition.
  void settle(double t, Eigen::VectorXd& y) const override;

  /// y at the model's initial state, in the current partition.
  [[nodiscard]] Eigen::VectorXd initial_state() const;
  /// Everything at (t, y): u, u', u'' and λ of the full equations (f_con = −Aᵀλ).
  struct Full {
    Eigen::VectorXd u, v, a, lambda;
  };
  [[nodiscard]] Full full(double t, const ConstRef& y) const;

  [[nodiscard]] const CoordinatePartition& partition() const { return partition_; }
  [[nodiscard]] const std::vector<Repartition>& repartitions() const { return log_; }
  /// Newton iterations and evaluations so far (the summary's note).
  [[nodiscard]] long newton_iterations() const { return iterations_; }

  /// Re-partition when the partition's quality falls below this fraction of the quality it had
  /// when chosen: a tenth, so that a partition is kept while the dependent coordinates move at
  /// most ten times as far per unit of the independent ones as they did then, and qualities that
  /// merely vary along the motion do not restart the integrator.
  static constexpr double kRepartitionFraction = 0.1;
  /// The Newton iteration's cap: from a warm start within a step of the solution it converges
  /// quadratically in two or three; more means the step went too far (CVODE then cuts it).
  static constexpr int kMaxNewtonIterations = 12;
  /// The largest state (2(n − m) unknowns) whose Newton systems use CVODE's dense
  /// difference-quotient Jacobian: 64 unknowns are 4096 entries and 64 right-hand sides a
  /// Jacobian, a fixed-size block; every mechanism of models/scenes/ stays below it (results
  /// unchanged), a chain of 32 bars or more goes above.
  static constexpr int kDenseJacobianLimit = 64;

 private:
  /// u on the constraints at (t, q_i) (Newton), with A(t, u) evaluated and A_d factored at it.
  /// Throws RecoverableError when the iteration does not converge or A_d is singular.
  void solve_positions(double t, const ConstRef& q) const;
  /// φ at (t, u) into phi_: the system's position rows, and a·u − g(t) for integrable
  /// velocity rows (linear, constant coefficients).
  void constraints_at(double t) const;
  /// A(t, u) into a_, A_d factored; false when singular.
  bool factor_dependent(double t) const;
  /// u'' and λ at (t, u_, v_) from the KKT system.
  void accelerations(double t) const;
  /// Uses `p` from here on (its LU pattern analysed, its quality at A(t, u_) the reference).
  void adopt(CoordinatePartition p, double t) const;

  const Model& model_;
  std::unique_ptr<MechanicalSystem> system_;
  int n_, m_, ni_;
  std::vector<int> integrable_velocity_rows_;
  double tolerance_ = 0.0;
  std::optional<bool> matrix_free_;  ///< set_matrix_free; unset: by size
  mutable CoordinatePartition partition_;
  mutable double reference_quality_ = 1.0;
  mutable std::optional<CoordinatePartition> pending_;
  mutable std::vector<Repartition> log_;
  mutable long iterations_ = 0;
  mutable Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
  /// [M Aᵀ; A 0], factored at every evaluation under the analysis made for its pattern (that
  /// analysis, BTF and AMD, made afresh at each evaluation was 40 % of A02's profile).
  mutable KluByPattern kkt_lu_;
  mutable Eigen::VectorXd u_, v_, a_acc_, lambda_, phi_, psi_, gamma_, force_;
  mutable Eigen::SparseMatrix<double> a_, ad_;
};

}  // namespace condyn
