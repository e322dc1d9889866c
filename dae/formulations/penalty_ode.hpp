#pragma once
/// The penalty formulation (the chapter's Table 5.3, "standard, one pass"): no multiplier
/// unknowns. Each constraint becomes a penalty element whose force plays the multiplier:
///
///   λ = w φ    on position rows (a spring of stiffness w along the constraint normal)
///   λ = c ψ    on velocity rows (a dashpot)
///   y = [u; v],  u' − v = 0,  M v' − f(t, u, v) + Aᵀ λ(t, u, v) = 0   (all differential)
///
/// The constraints hold only to about |f_con| / w, and the penalty springs add a frequency
/// √(w / m) that makes the system stiff: the cost is accuracy (small w) or stiffness (large w).
/// Reactions are the element forces, f_con = −Aᵀλ, the same meaning as in every other scheme.

#include <Eigen/SparseLU>
#include <memory>
#include <string>

#include "dae/interface/dae_problem.hpp"
#include "dae/interface/held_massless.hpp"
#include "dae/linsolve/block_jacobian.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/model.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

struct PenaltyWeights {
  double position = 0.0;  ///< w
  double velocity = 0.0;  ///< c
  std::string rule;       ///< how they were chosen, printed in the summary
};

/// From [solve] penalty = { weight = w } or by default w = 1e4 · max_i K_ii: the penalty springs
/// are four orders stiffer than the stiffest element, so the constraint error is about 1e-4 of
/// the elastic deformation. Without stiffness, w = 1e4 · m_max (2π / output_step)². Velocity rows
/// get c = √(w · m_max), the critical dashpot of the largest mass on a spring w.
[[nodiscard]] PenaltyWeights penalty_weights(const Model& model, const SolveSpec& settings);

class PenaltyOde final : public DaeProblem {
 public:
  /// Evaluates its own clone of `system`. Throws std::invalid_argument for curvature terms.
  PenaltyOde(const MechanicalSystem& system, const PenaltyWeights& weights);

  [[nodiscard]] int size() const override { return 2 * n_; }
  void begin_segment(double t0) override { system_->begin_segment(t0); }
  void residual(double t, ConstRef y, ConstRef yp, Ref r) const override;
  [[nodiscard]] const JacobianPattern& jacobian_pattern() const override {
    return jacobian_.pattern();
  }
  void fill_jacobian(double t, ConstRef y, ConstRef yp, double cj, JacobianMap J) const override;
  [[nodiscard]] std::vector<UnknownKind> unknown_kinds() const override {
    return condyn::unknown_kinds(n_);
  }
  /// All differential, but the velocities of massless DOFs (algebraic:
  /// dae/interface/held_massless.hpp).
  [[nodiscard]] Eigen::VectorXd differential_id() const override {
    return held_differential_id(held_.get(), size());
  }
  [[nodiscard]] Eigen::VectorXd variable_index() const override {
    return held_variable_index(held_.get(), size());
  }
  /// The massless DOFs' velocities are left out of the error test, as under elimination
  /// (dae/formulations/reduced_ode.hpp says why).
  [[nodiscard]] bool suppress_algebraic_error() const override { return held_ != nullptr; }
  /// y' = [v; M⁻¹(f − Aᵀλ)]. Massless DOFs, which the penalty springs hold when constraints
  /// touch them, get their u (or v, with damping) from their rows
  /// (dae/interface/held_massless.hpp).
  void make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const override;

  /// IDA's Newton systems condensed to u, as elimination's (dae/formulations/reduced_ode.hpp):
  /// (K_w + cj C_w + cj² M) du = r2 + (C_w + cj M) r1, dv = cj du − r1, with the penalized
  /// K_w = K + w N_pᵀN_p and C_w = C + c N_vᵀN_v (N the rows' unit normals): symmetric, and
  /// positive definite for a stable model, so CHOLMOD can factor it. The model is linear (a
  /// nonlinear one runs the augmented Lagrangian), so the matrices are those at t = 0.
  [[nodiscard]] std::unique_ptr<NewtonSystem> newton_system() const override;

  /// f(t, u, v) − Aᵀλ(t, u, v): what M v' balances.
  [[nodiscard]] Eigen::VectorXd net_force(double t, const Eigen::VectorXd& y) const;

  /// The penalty element forces λ at a state.
  [[nodiscard]] Eigen::VectorXd multipliers(double t, const Eigen::VectorXd& y) const;

 private:
  std::unique_ptr<MechanicalSystem> system_;  ///< this run's evaluator
  PenaltyWeights weights_;
  int n_, m_;
  Eigen::VectorXd row_weight_;  ///< w on position rows, c on velocity rows
  /// 1/|a_i|: row i scaled by it is its unit normal.
  Eigen::VectorXd row_scale_;
  /// Diagonal: 1 on the position rows (velocity rows), 0 elsewhere.
  Eigen::SparseMatrix<double> position_mask_, velocity_mask_;
  /// The rows' unit normals, diag(row_scale_) A.
  [[nodiscard]] Eigen::SparseMatrix<double> normals(const Eigen::SparseMatrix<double>& A) const;
  BlockJacobian jacobian_;
  /// Massless DOFs, held by stiffness, damping or the penalty elements (the penalized K and C:
  /// K + w A_pᵀA_p, C + c A_vᵀA_v), or null.
  std::shared_ptr<const HeldMassless> held_;
  // Scratch of the residual (the hot path): sized once, no allocation per call. Not
  // thread-safe: one problem object per integration.
  mutable Eigen::VectorXd force_, rows_;
};

}  // namespace condyn
