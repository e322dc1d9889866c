// Accelerations from the equations of motion at an output state (dae/acceleration.hpp).

#include "dae/acceleration.hpp"

#include <limits>
#include <stdexcept>

namespace condyn {

void AccelerationFromForces::factor(const Eigen::SparseMatrix<double>& mass) {
  const Eigen::Index n = mass.rows();
  massless_ = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (mass.coeff(i, i) == 0.0) massless_[i] = 1.0;
  }
  // M is positive semi-definite: a zero diagonal entry is a zero row and column, so a unit there
  // leaves the other DOFs' block, and their accelerations, untouched.
  Eigen::SparseMatrix<double> regular = mass;
  if (massless_.sum() > 0.0) {
    Eigen::SparseMatrix<double> unit(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (massless_[i] != 0.0) unit.insert(i, i) = 1.0;
    }
    regular += unit;
  }
  ldlt_.compute(regular);
  if (ldlt_.info() != Eigen::Success)
    throw std::runtime_error("accelerations: the mass matrix could not be factored");
  factored_ = true;
}

Eigen::VectorXd AccelerationFromForces::operator()(MechanicalSystem& system, double t,
                                                   const Eigen::VectorXd& u,
                                                   const Eigen::VectorXd& v,
                                                   const Eigen::VectorXd& reaction) {
  if (!factored_ || !constant_mass_) factor(system.mass(t, u));
  Eigen::VectorXd rhs(u.size());
  system.force(t, u, v, rhs);
  rhs += reaction;
  for (Eigen::Index i = 0; i < rhs.size(); ++i) {
    if (massless_[i] != 0.0) rhs[i] = 0.0;
  }
  Eigen::VectorXd a = ldlt_.solve(rhs);
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    if (massless_[i] != 0.0) a[i] = std::numeric_limits<double>::quiet_NaN();
  }
  return a;
}

}  // namespace condyn
