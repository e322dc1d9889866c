#pragma once
/// The elimination path's reduced system as a first-order ODE for IDA, all components
/// differential:
///
///   y = [û; w],   F(t, y, y') = [ û' − w ;  M̂ w' + Ĉ w + K̂ û − f̂(t) ] = 0.
///
/// Its Jacobian is dF/dy + cj dF/dy' = [[cj I, −I], [K̂, Ĉ + cj M̂]].

#include <Eigen/SparseCholesky>
#include <memory>
#include <optional>

#include "dae/formulations/reduced_system.hpp"
#include "dae/interface/dae_problem.hpp"
#include "dae/interface/held_massless.hpp"
#include "dae/linsolve/block_jacobian.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/rayleigh.hpp"
#include "models/core/symmetric_products.hpp"

namespace condyn {

class ReducedOde final : public DaeProblem {
 public:
  /// Keeps references to both arguments. Massless masters that no kept row touches are held by
  /// their stiffness rows (dae/interface/held_massless.hpp). Throws std::invalid_argument when M̂ is
  /// singular otherwise, naming the master DOFs without mass.
  ReducedOde(const Model& model, const ReducedSystem& reduced);

  [[nodiscard]] int size() const override { return 2 * nm_; }
  void begin_segment(double t0) override { segment_start_ = t0; }
  void residual(double t, ConstRef y, ConstRef yp, Ref r) const override;
  [[nodiscard]] const JacobianPattern& jacobian_pattern() const override {
    return jacobian_.pattern();
  }
  void fill_jacobian(double t, ConstRef y, ConstRef yp, double cj, JacobianMap J) const override;
  /// û are master displacements, w their velocities.
  [[nodiscard]] std::vector<UnknownKind> unknown_kinds() const override {
    return condyn::unknown_kinds(nm_);
  }
  /// All differential, but the velocities of massless masters held by stiffness (algebraic;
  /// dae/interface/held_massless.hpp).
  [[nodiscard]] Eigen::VectorXd differential_id() const override {
    return held_differential_id(held_.get(), size());
  }
  [[nodiscard]] Eigen::VectorXd variable_index() const override {
    return held_variable_index(held_.get(), size());
  }
  /// The held masters' velocities (algebraic) are left out of the error test, as under every
  /// multiplier scheme: their accuracy follows from the differential unknowns'. In the test, a
  /// damped one (index 1) made nearly every step fail it (docs/benchmarks.md).
  [[nodiscard]] bool suppress_algebraic_error() const override { return held_ != nullptr; }
  /// Every unknown differential and in the error test, unless a massless master is held.
  [[nodiscard]] bool reuses_newton_matrix() const override { return held_ == nullptr; }
  void make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const override;
  /// IDA's Newton systems condensed to û: (K̂ + cj Ĉ + cj² M̂) dû = r2 + (Ĉ + cj M̂) r1,
  /// dw = cj dû − r1 (dae/linsolve/condensed_newton.hpp without constraints).
  [[nodiscard]] std::unique_ptr<NewtonSystem> newton_system() const override;

  /// û'' = M̂⁻¹ (f̂(t) − Ĉ w − K̂ û), steps on at t (right limit); 0 on massless masters held by
  /// stiffness (their rows of M̂ are zero, so no reaction depends on it).
  [[nodiscard]] Eigen::VectorXd acceleration(double t, const Eigen::VectorXd& x,
                                             const Eigen::VectorXd& w) const;

 private:
  /// f̂ − K̂ û − Ĉ w.
  [[nodiscard]] Eigen::VectorXd rhs_at(const Eigen::VectorXd& f, const Eigen::VectorXd& x,
                                       const Eigen::VectorXd& w) const;
  const Model& model_;
  const ReducedSystem& reduced_;
  int nm_;
  /// M̂ factored, when no master is massless; constant, shared by copies (a plan's ODE and the
  /// copy each run integrates).
  std::shared_ptr<const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> mass_;
  std::shared_ptr<const HeldMassless> held_;  ///< massless masters held by stiffness, or null
  BlockJacobian jacobian_;
  /// M̂ ẇ + K̂ û + Ĉ w in one pass on two lanes, on large models (null on small ones, where
  /// Eigen's products serve); with Rayleigh damping (rayleigh_) Ĉ w is a₀ M̂ w + a₁ K̂ w, read
  /// from M̂ and K̂ in the same pass: M̂ (ẇ + a₀ w) + K̂ (û + a₁ w).
  std::shared_ptr<const SymmetricProducts> products_;
  std::optional<RayleighCoefficients> rayleigh_;
  /// Load steps with start <= it are on (begin_segment); before any segment, those at t.
  std::optional<double> segment_start_;
};

}  // namespace condyn
