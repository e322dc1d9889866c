#pragma once
/// The general constrained mechanical system the multiplier formulations are written against:
///
///   M(u) u'' = f(t, u, u') − A(t, u)ᵀ λ                      (f_con = −Aᵀλ)
///   φ_i(t, u) = 0              for position-level rows i     (holonomic)
///   ψ_i(t, u, u') = 0          for every row i: the velocity-level form
///                              (A_i u' − g_i' for position rows, A_i u' − h_i for velocity rows)
///   A(t, u) u'' = γ(t, u, u')  the acceleration-level form (γ = g'' or h' for linear rows; for
///                              nonlinear rows it carries the curvature terms)
///
/// Linear models are one case of it (dae/linear_system.hpp): constant M, A, and derivative terms
/// that vanish. Every Jacobian block is reported with a fixed sparsity pattern, so a formulation
/// assembles its Jacobian pattern once.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

namespace condyn {

class MechanicalSystem {
 public:
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  using Ref = Eigen::Ref<Eigen::VectorXd>;
  using Sparse = Eigen::SparseMatrix<double>;

  virtual ~MechanicalSystem() = default;

  [[nodiscard]] virtual int dofs() const = 0;
  [[nodiscard]] virtual int constraints() const = 0;
  /// true for rows written at position level (they get φ and, under GGL, a μ).
  [[nodiscard]] virtual const std::vector<bool>& position_rows() const = 0;

  /// M(u), n x n, its pattern fixed. The reference stays valid until the next call (a linear
  /// system returns its constant matrix: no copy on the residual's hot path).
  [[nodiscard]] virtual const Sparse& mass(double t, ConstRef u) const = 0;
  /// f(t, u, u'): applied loads minus internal forces (K u + C u' for a linear model). Steps are
  /// on when start <= step_reference.
  virtual void force(double t, double step_reference, ConstRef u, ConstRef v, Ref f) const = 0;
  /// df/du and df/du', n x n each, patterns fixed; references valid until the next call.
  [[nodiscard]] virtual const Sparse& force_jacobian_u(double t, ConstRef u, ConstRef v) const = 0;
  [[nodiscard]] virtual const Sparse& force_jacobian_v(double t, ConstRef u, ConstRef v) const = 0;

  /// A(t, u), m x n, pattern fixed; the reference stays valid until the next call.
  [[nodiscard]] virtual const Sparse& constraint_jacobian(double t, ConstRef u) const = 0;
  /// φ (m; zero on velocity rows).
  virtual void position_residual(double t, ConstRef u, Ref phi) const = 0;
  /// ψ (m).
  virtual void velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) const = 0;
  /// γ (m).
  virtual void acceleration_bias(double t, ConstRef u, ConstRef v, Ref gamma) const = 0;

  /// State derivatives that vanish for linear constraints with constant coefficients:
  /// d(Aᵀw)/du (n x n), d(A a)/du, dψ/du, dγ/du, dγ/du' (m x n). A linear system reports empty
  /// (0 x 0) matrices and the formulations leave them out of the pattern.
  [[nodiscard]] virtual bool has_curvature() const { return false; }
};

}  // namespace condyn
