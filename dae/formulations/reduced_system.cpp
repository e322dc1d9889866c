#include "dae/formulations/reduced_system.hpp"

#include <string>

#include "dae/interface/scheme_not_applicable.hpp"

namespace condyn {

ReducedSystem reduce(const Model& model, const std::vector<std::string>& preferred_slaves) {
  std::vector<int> preferred;
  preferred.reserve(preferred_slaves.size());
  for (const auto& name : preferred_slaves) preferred.push_back(model.dof_at(name));
  ReducedSystem r;
  r.named_slaves = !preferred.empty();
  try {
    r.transform = master_slave_transform(model.A, preferred);
  } catch (const CoupledGroupTooLarge& e) {
    // The request, not the solver, is at fault: bad input for the CLI (exit 2), and auto falls
    // back to GGL as for any scheme that cannot treat the model.
    throw SchemeNotApplicable(
        "elimination: constraint '" +
        model.constraints[static_cast<std::size_t>(e.first_row)].name + "'" +
        (e.rows > 1 ? " and " + std::to_string(e.rows - 1) + " others" : std::string()) + ": " +
        e.what());
  }
  const auto& T = r.transform.T;
  const auto& G = r.transform.G;
  const Eigen::SparseMatrix<double> Tt = T.transpose();
  r.M = Tt * model.M * T;
  r.K = Tt * *model.K * T;
  const int nm = static_cast<int>(T.cols());
  if (model.has_damping()) {
    r.C = Tt * model.C * T;
  } else {
    r.C.resize(nm, nm);
  }
  // Products right to left: K G is n x m with the slaves' neighbours only.
  r.FK = -(Tt * Eigen::SparseMatrix<double>(*model.K * G));
  r.FM = -(Tt * Eigen::SparseMatrix<double>(model.M * G));
  if (model.has_damping()) {
    r.FC = -(Tt * Eigen::SparseMatrix<double>(model.C * G));
  } else {
    r.FC.resize(nm, model.constraint_count());
  }
  // B (n x loads): a column per load, e_dof or its pattern; then Tᵀ B.
  std::vector<Eigen::Triplet<double>> b;
  for (std::size_t k = 0; k < model.loads.size(); ++k) {
    const Load& load = model.loads[k];
    const auto col = static_cast<int>(k);
    if (load.dof >= 0) {
      b.emplace_back(load.dof, col, 1.0);
    } else {
      for (Eigen::SparseVector<double>::InnerIterator it(load.pattern); it; ++it)
        b.emplace_back(static_cast<int>(it.index()), col, it.value());
    }
  }
  Eigen::SparseMatrix<double> B(model.dofs(), static_cast<Eigen::Index>(model.loads.size()));
  B.setFromTriplets(b.begin(), b.end());
  r.loads = Tt * B;
  for (const auto& c : model.constraints) r.rheonomic = r.rheonomic || !c.position_value.is_zero();
  return r;
}

Eigen::VectorXd ReducedSystem::forces(const Model& model, double t, double step_reference) const {
  Eigen::VectorXd values(static_cast<Eigen::Index>(model.loads.size()));
  for (std::size_t k = 0; k < model.loads.size(); ++k) {
    values[static_cast<Eigen::Index>(k)] = model.loads[k].value.derivative(0, t, step_reference);
  }
  Eigen::VectorXd f = loads * values;
  // Homogeneous scleronomic constraints have no transfer forces: skip the time functions.
  if (rheonomic) {
    f += FK * model.position_rhs(0, t) + FM * model.position_rhs(2, t);
    if (model.has_damping()) f += FC * model.position_rhs(1, t);
  }
  return f;
}

}  // namespace condyn
