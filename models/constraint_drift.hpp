#pragma once
/// How far a state is from the constraints, for drift logs and trajectories.

#include <Eigen/Dense>
#include <memory>
#include <utility>

#include "models/model.hpp"

namespace condyn {

/// Max-norm drifts: position over position-level constraints |φ| (|a·u − g| for linear rows),
/// velocity over all constraints |ψ| (|a·v − g'| or |a·v − h| for linear rows); 0 without
/// constraints. One object per run: it evaluates nonlinear rows with its own evaluator.
class ConstraintDrift {
 public:
  explicit ConstraintDrift(const Model& model);  ///< keeps a reference
  [[nodiscard]] std::pair<double, double> operator()(double t, const Eigen::VectorXd& u,
                                                     const Eigen::VectorXd& v);

 private:
  const Model& model_;
  std::unique_ptr<MechanicalSystem> nonlinear_;  ///< nonlinear models only
  Eigen::VectorXd phi_, psi_;
};

}  // namespace condyn
