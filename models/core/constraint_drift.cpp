#include "models/core/constraint_drift.hpp"

#include <algorithm>
#include <cmath>

namespace condyn {

ConstraintDrift::ConstraintDrift(const Model& model)
    : model_(model),
      nonlinear_(model.is_nonlinear() ? model.evaluator() : nullptr),
      phi_(model.constraint_count()),
      psi_(model.constraint_count()),
      inverse_scale_(Eigen::VectorXd::Ones(model.constraint_count())) {
  Eigen::VectorXd largest = Eigen::VectorXd::Zero(model.constraint_count());
  if (model.A.rows() == largest.size()) {
    for (int k = 0; k < model.A.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(model.A, k); it; ++it) {
        largest[it.row()] = std::max(largest[it.row()], std::abs(it.value()));
      }
    }
  }
  for (Eigen::Index i = 0; i < largest.size(); ++i) {
    if (largest[i] > 0.0) inverse_scale_[i] = 1.0 / largest[i];
  }
}

std::pair<double, double> ConstraintDrift::operator()(double t, const Eigen::VectorXd& u,
                                                      const Eigen::VectorXd& v) {
  relative_position_ = 0.0;
  worst_row_ = -1;
  if (nonlinear_) {
    nonlinear_->position_residual(t, u, phi_);
    nonlinear_->velocity_residual(t, u, v, psi_);
    // position_residual leaves velocity-level rows at 0.
    if (phi_.size() == inverse_scale_.size() && phi_.size() > 0) {
      Eigen::Index row = 0;
      relative_position_ = phi_.cwiseAbs().cwiseProduct(inverse_scale_).maxCoeff(&row);
      if (relative_position_ > 0.0) worst_row_ = static_cast<int>(row);
    }
    return {phi_.size() ? phi_.lpNorm<Eigen::Infinity>() : 0.0,
            psi_.size() ? psi_.lpNorm<Eigen::Infinity>() : 0.0};
  }
  double pos = 0.0, vel = 0.0;
  for (std::size_t i = 0; i < model_.constraints.size(); ++i) {
    const auto& c = model_.constraints[i];
    double au = 0.0, av = 0.0;
    for (const auto& [d, a] : c.coefficients) {
      au += a * u[d];
      av += a * v[d];
    }
    if (c.level == ConstraintLevel::position) {
      const double phi = std::abs(au - c.value.value(t));
      pos = std::max(pos, phi);
      const double relative = phi * inverse_scale_[static_cast<Eigen::Index>(i)];
      if (relative > relative_position_) {
        relative_position_ = relative;
        worst_row_ = static_cast<int>(i);
      }
      vel = std::max(vel, std::abs(av - c.value.derivative(1, t)));
    } else {
      vel = std::max(vel, std::abs(av - c.value.value(t)));
    }
  }
  return {pos, vel};
}

}  // namespace condyn
