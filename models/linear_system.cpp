#include "models/linear_system.hpp"

namespace condyn {

LinearSystem::LinearSystem(const Model& model)
    : model_(model), rows_(model.constraints), minus_K_(-model.K), minus_C_(-model.C) {
  for (const auto& c : model.constraints) {
    position_.push_back(c.level == ConstraintSpec::Level::position);
  }
  conservative_ = model.is_conservative();
}

void LinearSystem::force(double t, double step_reference, ConstRef u, ConstRef v, Ref f) const {
  f.noalias() = minus_K_ * u;
  if (model_.has_damping()) f.noalias() += minus_C_ * v;
  for (const auto& load : model_.loads) f[load.dof] += load.value.derivative(0, t, step_reference);
}

std::optional<double> LinearSystem::energy(double t, ConstRef u, ConstRef v) const {
  if (!conservative_) return std::nullopt;
  return 0.5 * v.dot(model_.M * v) + 0.5 * u.dot(model_.K * u) - model_.applied_forces(t).dot(u);
}

}  // namespace condyn
