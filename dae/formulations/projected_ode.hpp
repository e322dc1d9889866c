#pragma once
/// The projection scheme: the index-1 formulation as an ODE, y = [u; v],
///
///   u' = v,   v' = a  with  [M Aᵀ; A 0] [a; λ] = [f(t, u, v); γ]   (λ eliminated),
///
/// integrated by CVODE, which after every step projects the state back onto the constraint
/// manifold (CVodeSetProjFn), M-weighted (the closest point in the kinetic-energy metric):
///
///   u ← u + Δu,  [M A_pᵀ; A_p 0] [Δu; ·] = [0; −φ_p(t, u)]    (position rows)
///   v ← v + Δv,  [M Aᵀ; A 0] [Δv; ·] = [0; −ψ(t, u, v)]       (all rows)
///
/// (for a positive definite M, Δu = −M⁻¹A_pᵀ (A_p M⁻¹ A_pᵀ)⁻¹ φ_p; the KKT form also serves
/// massless DOFs that the constraints fix, such as supports).
/// and projects the local error estimate the same way. Why CVODE and not IDA: IDA 6.4 has no
/// projection hook, and projecting between IDA steps needs IDAReInit, which restarts the BDF
/// method at order 1 after every step. CVODE's projection is part of its step, so the method
/// keeps its order and its history stays consistent with the projected solution.
///
/// For nonlinear constraints (A = A(t, u)) the position projection is a Gauss-Newton iteration of
/// the same step, with A and M re-evaluated at each iterate, until the correction is at roundoff.
///
/// Massless DOFs held by stiffness (dae/interface/held_massless.hpp; linear models): their momentum
/// rows are algebraic, K_h· u = f_h (undamped) or C_h· v + K_h· u = f_h (damped), and M cannot give
/// their accelerations. The ODE takes them from the rows differentiated, K_h· a = f̈_h and
/// C_h· a + K_h· v = ḟ_h (the other DOFs' accelerations do not depend on them: M's and A's
/// columns h are zero), and keeps the rows as invariants: each projection and each segment start
/// settles u_h and v_h on them after the constraint rows (HeldMassless::settle). That is the
/// limit of the projection in the metric M + εI as ε → 0: the other DOFs move as in the
/// M-weighted projection, the held ones follow their rows.
///
/// Costs: for constant M and A the KKT system is factored once and every right-hand side is one
/// solve; with curvature (M or A varying) it is re-factored at every evaluation. CVODE's Newton
/// systems are the sparse saddle-point solve of dae/formulations/kkt_newton.hpp (exact, n + m
/// unknowns): constant for a linear model, linearised at CVODE's predicted state from the
/// system's curvature blocks for a nonlinear one. Needs M positive definite on the constraints'
/// null space (the KKT matrices nonsingular).

#include <Eigen/SparseLU>

#include "dae/interface/held_massless.hpp"
#include "dae/interface/ode_problem.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "dae/linsolve/kkt.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

class ProjectedOde final : public OdeProblem {
 public:
  /// Evaluates its own clones of `system`; `linear`: M, C, K and A are constant (Model::nonlinear
  /// false), so the sparse Newton solve is exact. `loads`: the model whose applied loads (and
  /// their time derivatives) the held massless DOFs' rows need, for a linear system that has
  /// such DOFs (null: sizes only, rhs() and project() are not called). Throws
  /// std::invalid_argument when a KKT matrix is singular at the initial state u0.
  ProjectedOde(const MechanicalSystem& system, const Eigen::VectorXd& u0, bool linear,
               const Model* loads = nullptr);

  [[nodiscard]] int size() const override { return 2 * n_; }
  void begin_segment(double t0) override {
    system_->begin_segment(t0);
    segment_start_ = t0;
  }
  void rhs(double t, ConstRef y, Ref ydot) const override;
  [[nodiscard]] bool has_projection() const override { return m_ > 0 || held_ != nullptr; }
  void settle(double t, Eigen::VectorXd& y) const override;
  [[nodiscard]] std::vector<UnknownKind> unknown_kinds() const override {
    return condyn::unknown_kinds(n_);
  }
  bool project(double t, ConstRef y, Ref corr, const Eigen::VectorXd& settled) const override;
  void project_error(Ref err) const override;
  /// The sparse saddle-point solve (dae/formulations/kkt_newton.hpp): constant for a linear
  /// model; for a nonlinear one it evaluates this ODE's own evaluator, so it must not outlive
  /// the ODE.
  [[nodiscard]] std::unique_ptr<NewtonSystem> newton_system() const override;

  /// λ at a state, from the same KKT system (f_con = −Aᵀλ), with the loads on at t as outside
  /// the integration (the right limit at a load step).
  [[nodiscard]] Eigen::VectorXd multipliers(double t, const Eigen::VectorXd& y) const;

 private:
  /// [a; λ] from the KKT system at (t, u, v), with the forces of `loads_from` (the run's evaluator
  /// or the observer).
  [[nodiscard]] Eigen::VectorXd accelerations(MechanicalSystem& loads_from, double t,
                                              const ConstRef& u, const ConstRef& v) const;

  /// Everything the right-hand side and the projections need at one (t, u): the KKT matrices
  /// with all rows and with the position rows, factored. Their patterns do not change with the
  /// state, so KLU's analysis is done once per matrix; each factorization pivots afresh (the
  /// accelerations' accuracy must not depend on pivots chosen at another state).
  struct Factors {
    FixedPatternKlu kkt, kkt_p;
    /// Exact per-row powers of two (models/core/row_scales.hpp): A and Ap hold the rows scaled by
    /// them, so KKT pivots do not depend on a row's units (rows at 1e-200 left the KKT matrix
    /// singular to roundoff); residuals are scaled the same way, and multipliers back.
    Eigen::VectorXd scale;
    Eigen::SparseMatrix<double> A, Ap;  ///< all rows, position rows (scaled)
  };
  /// Factors at (t, u): the constant ones for a system without curvature, else recomputed into
  /// scratch. Throws std::runtime_error when a KKT matrix is singular there.
  const Factors& factors(double t, const ConstRef& u) const;
  void factor(double t, const ConstRef& u, Factors& f) const;
  /// The M-weighted correction Δ with B Δ = −r, B = A (all rows) or A_p (position rows).
  [[nodiscard]] Eigen::VectorXd correction(const FixedPatternKlu& kkt,
                                           const Eigen::VectorXd& r) const;

  /// The model the held massless DOFs' loads come from; throws std::logic_error without one.
  [[nodiscard]] const Model& loads() const;
  /// Sets the held massless DOFs' u and v from their rows at t (nothing without them).
  void settle_held(double t, Ref u, Ref v) const;

  std::unique_ptr<MechanicalSystem> system_;    ///< this run's evaluator
  std::unique_ptr<MechanicalSystem> observer_;  ///< outside any segment: for multipliers()
  int n_, m_;
  bool varying_;
  bool linear_;
  std::shared_ptr<const HeldMassless> held_;  ///< null: no massless DOFs held by stiffness
  const Model* loads_;
  double segment_start_ = 0.0;  ///< load steps with start <= it are on
  std::vector<int> position_rows_;
  Eigen::SparseMatrix<double> select_p_;
  Factors constant_;
  mutable Factors scratch_;
  mutable const Factors* last_ = nullptr;  ///< the factors of the last projection
  mutable Eigen::VectorXd force_, rows_;
};

}  // namespace condyn
