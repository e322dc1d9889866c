#include "dae/run/energy_balance.hpp"

#include <stdexcept>
#include <string>

namespace condyn {

std::vector<std::string> energy_column_names() {
  return {kEnergyColumns.begin(), kEnergyColumns.end()};
}

double energy_column(const EnergyBalance& b, std::size_t k) {
  switch (k) {
    case 0:
      return b.energy();
    case 1:
      return b.error();
    case 2:
      return b.kinetic;
    case 3:
      return b.potential;
    case 4:
      return b.dissipated;
    case 5:
      return b.work_loads;
    case 6:
      return b.work_constraints;
    default:
      throw std::out_of_range("energy column " + std::to_string(k));
  }
}

EnergyTerms::EnergyTerms(const Model& model) : model_(model), system_(model.evaluator()) {}

Eigen::VectorXd EnergyTerms::powers(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                    const Eigen::VectorXd& lambda) {
  const auto parts = system_->energy_parts(t, u, v);
  if (!parts) throw std::logic_error("energy balance of a model without energy parts");
  Eigen::VectorXd p(kIntegrals);
  p << parts->dissipation_power, parts->load_power, 0.0;
  // f_conᵀu' = −λᵀ(A u').
  if (model_.constraint_count() > 0) p[2] = -lambda.dot(system_->constraint_jacobian(t, u) * v);
  return p;
}

Eigen::VectorXd EnergyTerms::jump_work(double t, const Eigen::VectorXd& u,
                                       const Eigen::VectorXd& du) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(kIntegrals);
  if (du.size() == 0 || du.cwiseAbs().maxCoeff() == 0.0) return w;  // no DOF jumped
  const auto parts = system_->energy_parts(t, u, du);  // its "load power" is f_ext(t, u)ᵀdu
  if (!parts) throw std::logic_error("energy balance of a model without energy parts");
  w[1] = parts->load_power;
  return w;
}

EnergyBalance EnergyTerms::at(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& integrals) {
  const auto parts = system_->energy_parts(t, u, v);
  if (!parts || integrals.size() != kIntegrals) {
    throw std::logic_error("energy balance without its parts or integrals");
  }
  EnergyBalance b;
  b.kinetic = 0.5 * v.dot(system_->mass(t, u) * v);
  b.potential = parts->potential;
  b.dissipated = integrals[0];
  b.work_loads = integrals[1];
  b.work_constraints = integrals[2];
  return b;
}

}  // namespace condyn
