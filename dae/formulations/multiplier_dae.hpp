#pragma once
/// The multiplier formulations, first-order form y = [u; v; λ; μ] (μ only under GGL, and only for
/// position-level rows):
///
///   u' − v (+ A_pᵀ μ)          = 0
///   M v' − f(t, u, v) + Aᵀ λ   = 0                      (f_con = −Aᵀλ, the chapter's sign)
///   index1:     A v' − γ                        = 0     (acceleration level, no stabilization)
///   baumgarte:  A v' − γ + 2α ψ + β² φ          = 0     (φ only on position rows)
///   ggl:        ψ = 0 and φ_p = 0        (stabilized index 2, Gear-Gupta-Leimkuhler)
///   index2:     ψ = 0                    (velocity level, no stabilization)
///   index3:     φ = 0 on position rows, ψ = 0 on velocity rows   (the original DAE)
///
/// Velocity-level rows enter at their own level: ψ (index 2) under GGL, index2 and index3,
/// differentiated once (A v' = h') under index1 and Baumgarte. μ vanishes on exact solutions; it
/// is reported. u and v are differential; λ and μ algebraic. Indices
/// (DaeProblem::variable_index): under index1 and Baumgarte everything is index 1; under GGL and
/// index2, λ and μ are index 2; under index3, v is index 2 and λ index 3 on position rows (2 on
/// velocity rows). Higher-index components are out of the error test and get (h/T)^(k−1)-scaled
/// Newton weights (T the model's time scale, dae/formulations/model_scales.hpp).

#include <Eigen/SparseLU>
#include <functional>

#include "dae/interface/dae_problem.hpp"
#include "dae/interface/held_massless.hpp"
#include "dae/linsolve/block_jacobian.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/scheme.hpp"

namespace condyn {

class MultiplierDae final : public DaeProblem {
 public:
  /// Evaluates its own clone of `system`. `scheme` is index1, baumgarte, ggl, index2 or index3
  /// (else std::invalid_argument); alpha and beta are used by Baumgarte only. `linear`: the
  /// system has constant M, C, K, A, so index1's and GGL's Newton systems can be solved
  /// condensed (newton_system()).
  MultiplierDae(const MechanicalSystem& system, Scheme scheme, double alpha = 0.0,
                double beta = 0.0, bool linear = false);

  [[nodiscard]] int size() const override { return mu_at() + p_; }
  void begin_segment(double t0) override { system_->begin_segment(t0); }
  void residual(double t, ConstRef y, ConstRef yp, Ref r) const override;
  [[nodiscard]] const JacobianPattern& jacobian_pattern() const override {
    return jacobian_.pattern();
  }
  void fill_jacobian(double t, ConstRef y, ConstRef yp, double cj, JacobianMap J) const override;
  [[nodiscard]] Eigen::VectorXd differential_id() const override;
  [[nodiscard]] std::vector<UnknownKind> unknown_kinds() const override {
    return condyn::unknown_kinds(n_, m_, p_);
  }
  [[nodiscard]] Eigen::VectorXd multiplier_row_scales(double t,
                                                      const Eigen::VectorXd& y) const override;
  [[nodiscard]] Eigen::VectorXd multiplier_row_masses(double t,
                                                      const Eigen::VectorXd& y) const override;
  /// GGL and index3, which hold u on the position rows: the projection onto a row a (a
  /// correction along aᵀ that cancels a·δ, δ the step's local errors, each up to rtol |u_j|)
  /// moves DOF i by up to |a_i| Σ_j |a_j| |u_j| / |a|²: that is u_i's floor (the largest over
  /// its rows); GGL's v the same over every row (ψ = 0 through λ). A DOF at 0 beside moving ones
  /// (a conical pendulum's height in steady rotation) cannot be held to its own atol: GGL's μ,
  /// which grows with h, made every change of step size fail the error test, and the run
  /// crawled at order 1 to a result far off. The integrator applies the floors only once a run is
  /// caught that way (dae/integrators/ida_integrator.cpp): applied always, they cost Andrews'
  /// mechanism much of its accuracy (docs/schemes.md).
  bool error_scale_floors(double t, const ConstRef& y, Eigen::VectorXd& floor) const override;
  [[nodiscard]] Eigen::VectorXd variable_index() const override;
  /// index1 and GGL of a linear model: dae/linsolve/condensed_newton.hpp; else nothing.
  [[nodiscard]] std::unique_ptr<NewtonSystem> newton_system() const override;
  /// GGL: its ψ and φ rows, which have no y'. Not index2's or index3's: measured over the scenes
  /// of models/ and validation/, their nonlinear models took more Jacobian evaluations (index2)
  /// or more steps (index3) with the correction (docs/benchmarks.md).
  [[nodiscard]] std::vector<bool> algebraic_equations() const override;
  /// Baumgarte: λ carries the stabilization terms 2αψ + β²φ, which amplify the local errors of
  /// u and v by up to β²; in the error test it would force u's local error below tol/β²
  /// (the pendulum with large gains failed the error test at every step: docs/schemes.md). λ is
  /// left out of the error test; its accuracy follows from u's and v's.
  /// index1: λ is left out as well. It is an index-1 function of (u, v) (the KKT system), so its
  /// error follows from theirs; in the test its estimate carries the drift index1 lets grow, and
  /// the slider-crank (models/scenes/slider_crank.toml) at rtol 1e-10 took many times the steps,
  /// most of them failing, and ended less accurate (docs/schemes.md).
  [[nodiscard]] bool suppress_algebraic_error() const override {
    return scheme_ == Scheme::baumgarte || scheme_ == Scheme::index1;
  }
  /// Keeps u and v; λ and v' from [M Aᵀ; A 0][v'; λ] = [f; γ − stabilization]; μ = 0, u' = v.
  /// Massless DOFs held by stiffness: their u (undamped) or v (damped) are recomputed
  /// (dae/interface/held_massless.hpp).
  void make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const override;
  /// Systems with curvature (mechanisms, whose drives may be tables): v ← v + Δv with
  /// [M Aᵀ; A 0] [Δv; Λ] = [0; −ψ(t, u, v)], the least change of kinetic energy that meets the
  /// velocity rows at t (the drive's impulse Aᵀ Λ). Linear models keep their v.
  void jump_velocities(double t, Eigen::VectorXd& y) const override;

  /// y with the given u, v and zero multipliers.
  [[nodiscard]] Eigen::VectorXd pack(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const;
  [[nodiscard]] auto u(const Eigen::VectorXd& y) const { return y.segment(0, n_); }
  [[nodiscard]] auto v(const Eigen::VectorXd& y) const { return y.segment(n_, n_); }
  [[nodiscard]] auto lambda(const Eigen::VectorXd& y) const { return y.segment(lambda_at(), m_); }
  [[nodiscard]] auto mu(const Eigen::VectorXd& y) const { return y.segment(mu_at(), p_); }

 private:
  /// Offsets of λ and μ in y (u at 0, v at n).
  [[nodiscard]] int lambda_at() const { return 2 * n_; }
  [[nodiscard]] int mu_at() const { return 2 * n_ + m_; }

  /// Calls visit(row0, col0, S, scale) for every block of J = dF/dy + cj dF/dy' except the two
  /// identities of the u rows: the one list of blocks both the pattern (at construction) and
  /// the values (jacobian()) are made from. Empty blocks (linear systems' curvature) add nothing.
  /// The constraint rows' right-hand side of the consistency system: γ, less Baumgarte's
  /// 2αψ + β²φ.
  [[nodiscard]] Eigen::VectorXd constraint_rhs(double t, const Eigen::VectorXd& uu,
                                               const Eigen::VectorXd& vv) const;
  /// make_consistent with massless DOFs held by stiffness (dae/interface/held_massless.hpp).
  void make_consistent_held(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const;

  using BlockVisitor = std::function<void(int, int, const Eigen::SparseMatrix<double>&, double)>;
  void for_each_block(double t, ConstRef y, ConstRef yp, double cj,
                      const BlockVisitor& visit) const;

  std::unique_ptr<MechanicalSystem> system_;  ///< this run's evaluator
  Scheme scheme_;
  double alpha_, beta_;
  bool condensed_;
  int n_, m_, p_;
  std::vector<int> position_row_;              ///< μ index k -> constraint row
  Eigen::SparseMatrix<double> select_p_;       ///< p x m: picks the position rows (GGL's μ)
  Eigen::SparseMatrix<double> position_mask_;  ///< m x m diagonal: 1 on position rows
  Eigen::SparseMatrix<double> velocity_mask_;  ///< m x m diagonal: 1 on velocity rows
  BlockJacobian jacobian_;
  /// Massless DOFs held by stiffness (linear systems; dae/interface/held_massless.hpp), or null.
  std::shared_ptr<const HeldMassless> held_;
  /// index3: the DOFs whose velocities λ reaches (index 2); the others' are index 1.
  std::vector<bool> reached_;
  // Scratch of the residual (the hot path): sized once, no allocation per call. Not
  // thread-safe: one problem object per integration.
  mutable Eigen::VectorXd force_, rows_;
  /// Scratch of error_scale_floors (per step): Σ_j |a_j| |u_j| and |a|² per row.
  mutable Eigen::VectorXd row_reach_, row_norm2_;
};

}  // namespace condyn
