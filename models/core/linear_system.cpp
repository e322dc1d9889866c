#include "models/core/linear_system.hpp"

namespace condyn {

LinearSystem::LinearSystem(const Model& model) {
  auto d = std::make_shared<Data>();
  d->M = model.M;
  d->K = model.K.share();
  d->C = model.C;
  d->A = model.A;
  d->loads = model.loads;
  d->rows = LinearRows(model.constraints);
  for (const auto& c : model.constraints) {
    d->position.push_back(c.level == ConstraintLevel::position);
  }
  d->damped = model.has_damping();
  d->conservative = model.is_conservative();
  data_ = std::move(d);
}

void LinearSystem::force(double t, ConstRef u, ConstRef v, Ref f) {
  const Data& d = *data_;
  f.setZero();
  f.noalias() -= *d.K * u;
  if (d.damped) f.noalias() -= d.C * v;
  const double steps = steps_at(t);
  for (const auto& load : d.loads) load.add_to(f, load.value.derivative(0, t, steps));
}

std::optional<double> LinearSystem::energy(double t, ConstRef u, ConstRef v) {
  if (!data_->conservative) return std::nullopt;
  const Data& d = *data_;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(u.size());
  for (const auto& load : d.loads) load.add_to(f, load.value.derivative(0, t, t));
  return 0.5 * v.dot(d.M * v) + 0.5 * u.dot(*d.K * u) - f.dot(u);
}

std::optional<MechanicalSystem::EnergyParts> LinearSystem::energy_parts(double t, ConstRef u,
                                                                        ConstRef v) {
  const Data& d = *data_;
  EnergyParts parts;
  parts.potential = 0.5 * u.dot(*d.K * u);
  if (d.damped) parts.dissipation_power = v.dot(d.C * v);
  const double steps = steps_at(t);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(v.size());
  for (const auto& load : d.loads) load.add_to(f, load.value.derivative(0, t, steps));
  parts.load_power = f.dot(v);
  return parts;
}

}  // namespace condyn
