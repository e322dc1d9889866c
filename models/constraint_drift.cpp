#include "models/constraint_drift.hpp"

#include <algorithm>
#include <cmath>

namespace condyn {

ConstraintDrift::ConstraintDrift(const Model& model)
    : model_(model),
      nonlinear_(model.is_nonlinear() ? model.evaluator() : nullptr),
      phi_(model.constraint_count()),
      psi_(model.constraint_count()) {}

std::pair<double, double> ConstraintDrift::operator()(double t, const Eigen::VectorXd& u,
                                                      const Eigen::VectorXd& v) {
  if (nonlinear_) {
    nonlinear_->position_residual(t, u, phi_);
    nonlinear_->velocity_residual(t, u, v, psi_);
    return {phi_.size() ? phi_.lpNorm<Eigen::Infinity>() : 0.0,
            psi_.size() ? psi_.lpNorm<Eigen::Infinity>() : 0.0};
  }
  double pos = 0.0, vel = 0.0;
  for (const auto& c : model_.constraints) {
    double au = 0.0, av = 0.0;
    for (const auto& [d, a] : c.coefficients) {
      au += a * u[d];
      av += a * v[d];
    }
    if (c.level == ConstraintSpec::Level::position) {
      pos = std::max(pos, std::abs(au - c.value.value(t)));
      vel = std::max(vel, std::abs(av - c.value.derivative(1, t)));
    } else {
      vel = std::max(vel, std::abs(av - c.value.value(t)));
    }
  }
  return {pos, vel};
}

}  // namespace condyn
