#pragma once
/// How far a state is from the constraints, for drift logs and trajectories.

#include <Eigen/Dense>
#include <memory>
#include <utility>

#include "models/core/model.hpp"

namespace condyn {

/// Max-norm drifts: position over position-level constraints |φ| (|a·u − g| for linear rows),
/// velocity over all constraints |ψ| (|a·v − g'| or |a·v − h| for linear rows); 0 without
/// constraints. One object per run: it evaluates nonlinear rows with its own evaluator.
class ConstraintDrift {
 public:
  explicit ConstraintDrift(const Model& model);  ///< keeps a reference
  [[nodiscard]] std::pair<double, double> operator()(double t, const Eigen::VectorXd& u,
                                                     const Eigen::VectorXd& v);
  /// Of the last call: max over the position-level rows of |φ_i| / s_i, s_i the row's largest
  /// coefficient |A_ij| at t = 0 (a nonlinear row's gradient there). A length in the model's
  /// unit, whatever a row's own scale (a rod's row |x|² − L² drifts 2L times its stretch): the
  /// displacement error that would explain the drift, judged against the error test's rtol |u| +
  /// atol (SolveSummary::drift_warning).
  [[nodiscard]] double relative_position() const { return relative_position_; }
  /// Of the last call: the position-level row where relative_position() is reached (−1 when it
  /// is 0).
  [[nodiscard]] int worst_row() const { return worst_row_; }

 private:
  const Model& model_;
  std::unique_ptr<MechanicalSystem> nonlinear_;  ///< nonlinear models only
  Eigen::VectorXd phi_, psi_;
  Eigen::VectorXd inverse_scale_;  ///< 1 / s_i per row (1 for a row without a coefficient)
  double relative_position_ = 0.0;
  int worst_row_ = -1;
};

}  // namespace condyn
