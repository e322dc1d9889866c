#include "dae/linear_system.hpp"

namespace condyn {

LinearSystem::LinearSystem(const Model& model)
    : model_(model), minus_K_(-model.K), minus_C_(-model.C) {
  for (const auto& c : model.constraints) {
    position_.push_back(c.level == ConstraintSpec::Level::position);
    has_rhs_.push_back(!c.value.is_zero());
  }
}

double LinearSystem::rhs(std::size_t i, int order, double t) const {
  return has_rhs_[i] ? model_.constraints[i].value.derivative(order, t) : 0.0;
}

void LinearSystem::force(double t, double step_reference, ConstRef u, ConstRef v, Ref f) const {
  f.noalias() = minus_K_ * u;
  if (model_.has_damping()) f.noalias() += minus_C_ * v;
  for (const auto& load : model_.loads) f[load.dof] += load.value.derivative(0, t, step_reference);
}

void LinearSystem::position_residual(double t, ConstRef u, Ref phi) const {
  phi.setZero();
  for (std::size_t i = 0; i < position_.size(); ++i) {
    if (!position_[i]) continue;
    double au = 0.0;
    for (const auto& [d, a] : model_.constraints[i].coefficients) au += a * u[d];
    phi[static_cast<Eigen::Index>(i)] = au - rhs(i, 0, t);
  }
}

void LinearSystem::velocity_residual(double t, ConstRef /*u*/, ConstRef v, Ref psi) const {
  psi = model_.A * v;
  for (std::size_t i = 0; i < position_.size(); ++i) {
    psi[static_cast<Eigen::Index>(i)] -= rhs(i, position_[i] ? 1 : 0, t);
  }
}

void LinearSystem::acceleration_bias(double t, ConstRef /*u*/, ConstRef /*v*/, Ref gamma) const {
  for (std::size_t i = 0; i < position_.size(); ++i) {
    gamma[static_cast<Eigen::Index>(i)] = rhs(i, position_[i] ? 2 : 1, t);
  }
}

}  // namespace condyn
