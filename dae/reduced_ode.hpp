#pragma once
/// The elimination path's reduced system as a first-order ODE for IDA, all components
/// differential:
///
///   y = [û; w],   F(t, y, y') = [ û' − w ;  M̂ w' + Ĉ w + K̂ û − f̂(t) ] = 0.
///
/// Its Jacobian is dF/dy + cj dF/dy' = [[cj I, −I], [K̂, Ĉ + cj M̂]].

#include <Eigen/SparseCholesky>
#include <optional>

#include "dae/block_jacobian.hpp"
#include "dae/dae_problem.hpp"
#include "dae/elimination.hpp"

namespace condyn {

class ReducedOde final : public DaeProblem {
 public:
  /// Keeps references to both arguments. Throws std::invalid_argument when M̂ is singular, naming
  /// the master DOFs without mass.
  ReducedOde(const Model& model, const ReducedSystem& reduced);

  [[nodiscard]] int size() const override { return 2 * nm_; }
  void begin_segment(double t0) override { segment_start_ = t0; }
  void residual(double t, ConstRef y, ConstRef yp, Ref r) const override;
  [[nodiscard]] const Eigen::SparseMatrix<double>& jacobian_pattern() const override {
    return jacobian_.pattern();
  }
  void jacobian(double t, ConstRef y, ConstRef yp, double cj,
                Eigen::SparseMatrix<double>& J) const override;
  /// û are master displacements, w their velocities.
  [[nodiscard]] std::vector<UnknownKind> unknown_kinds() const override {
    return condyn::unknown_kinds(nm_);
  }
  [[nodiscard]] Eigen::VectorXd differential_id() const override {
    return Eigen::VectorXd::Ones(size());
  }
  void make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const override;
  /// IDA's Newton systems condensed to û: (K̂ + cj Ĉ + cj² M̂) dû = r2 + (Ĉ + cj M̂) r1,
  /// dw = cj dû − r1 (dae/condensed_newton.hpp without constraints).
  [[nodiscard]] std::unique_ptr<NewtonSystem> newton_system() const override;

  /// û'' = M̂⁻¹ (f̂(t) − Ĉ w − K̂ û), steps on at t (right limit).
  [[nodiscard]] Eigen::VectorXd acceleration(double t, const Eigen::VectorXd& x,
                                             const Eigen::VectorXd& w) const;

 private:
  const Model& model_;
  const ReducedSystem& reduced_;
  int nm_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> mass_;
  BlockJacobian jacobian_;
  /// Load steps with start <= it are on (begin_segment); before any segment, those at t.
  std::optional<double> segment_start_;
};

}  // namespace condyn
