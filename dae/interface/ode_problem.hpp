#pragma once
/// An ODE y' = F(t, y) with an invariant manifold it should stay on, as CVODE sees it.

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "dae/interface/unknown_kind.hpp"
#include "dae/linsolve/newton_system.hpp"

namespace condyn {

class OdeProblem {
 public:
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  using Ref = Eigen::Ref<Eigen::VectorXd>;

  virtual ~OdeProblem() = default;
  [[nodiscard]] virtual int size() const = 0;
  /// The integration segment starting at t0 begins (at the start of the run and at every load
  /// step): load steps with start <= t0 are on until the next call.
  virtual void begin_segment(double t0) = 0;
  /// ydot = F(t, y) in the current segment.
  virtual void rhs(double t, ConstRef y, Ref ydot) const = 0;
  /// The kind of each unknown, for its absolute tolerance; empty: all get the displacement atol.
  [[nodiscard]] virtual std::vector<UnknownKind> unknown_kinds() const { return {}; }
  /// True when the problem has an invariant to project onto after each step.
  [[nodiscard]] virtual bool has_projection() const = 0;
  /// corr such that y + corr lies on the manifold (CVodeSetProjFn). `settled`: per component of
  /// y, a correction small enough to stop an iteration that no longer shrinks it (one at the
  /// roundoff of large coordinates), a fraction of the error test's rtol |y_i| + atol_i.
  /// Returns false when the projection did not converge (CVODE then retries with a smaller step).
  virtual bool project(double t, ConstRef y, Ref corr, const Eigen::VectorXd& settled) const = 0;
  /// Places y on the invariant's algebraic rows at a segment start (t), before the integrator
  /// takes it: the rows that fix some unknowns outright (massless DOFs held by stiffness, which a
  /// load step may move). Nothing by default.
  virtual void settle(double /*t*/, Eigen::VectorXd& /*y*/) const {}
  /// Whether the integration should restart at t, the end of an accepted step at state y,
  /// because the problem re-expresses its state there (coordinate partitioning: a new partition
  /// when the dependent block grows ill-conditioned). settle() at that restart re-expresses y.
  /// No by default.
  // By-value Ref: the signature every override shares (the default ignores it).
  // NOLINTNEXTLINE(performance-unnecessary-value-param)
  [[nodiscard]] virtual bool wants_restart(double /*t*/, ConstRef /*y*/) const { return false; }
  /// Applies the projection's linearisation to an error estimate (CVodeSetProjErrEst).
  virtual void project_error(Ref err) const = 0;
  /// True for an ODE that is not stiff: CVODE then integrates it by Adams' methods with
  /// functional (fixed-point) iteration, no Newton system and no Jacobian at all
  /// (dae/formulations/augmented_lagrangian_ode.hpp); false: BDF with Newton.
  [[nodiscard]] virtual bool non_stiff() const { return false; }
  /// Its own solver of the Newton systems, or nothing: CVODE's dense difference-quotient Jacobian
  /// (size² entries, size right-hand sides a Jacobian), unless matrix_free().
  [[nodiscard]] virtual std::unique_ptr<NewtonSystem> newton_system() const { return nullptr; }
  /// Without newton_system(): true when CVODE is to solve the Newton systems (I − γJ) x = r by
  /// GMRES with its own difference-quotient products J v (one right-hand side each, nothing of
  /// size²), preconditioned by precondition(). False by default (the dense Jacobian).
  [[nodiscard]] virtual bool matrix_free() const { return false; }
  /// z ≈ (I − γJ)⁻¹ r for a matrix_free() problem's GMRES; z = r by default.
  // By-value Ref: the signature every override shares.
  // NOLINTNEXTLINE(performance-unnecessary-value-param)
  virtual void precondition(double /*gamma*/, ConstRef r, Ref z) const { z = r; }
};

}  // namespace condyn
