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

void LinearSystem::mass(double /*t*/, ConstRef /*u*/, Sparse& M) const { M = model_.M; }

void LinearSystem::force(double t, double step_reference, ConstRef u, ConstRef v, Ref f) const {
  f = model_.applied_forces(t, step_reference) - model_.K * u;
  if (model_.has_damping()) f.noalias() -= model_.C * v;
}

void LinearSystem::force_jacobian(double /*t*/, ConstRef /*u*/, ConstRef /*v*/, Sparse& f_u,
                                  Sparse& f_v) const {
  f_u = minus_K_;
  f_v = minus_C_;  // no nonzeros without damping: the block drops out of the pattern
}

void LinearSystem::constraint_jacobian(double /*t*/, ConstRef /*u*/, Sparse& A) const {
  A = model_.A;
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
