// Accelerations from the equations of motion at an output state
// (dae/formulations/acceleration.hpp).

#include "dae/formulations/acceleration.hpp"

#include <stdexcept>
#include <utility>

namespace condyn {

AccelerationFromForces::AccelerationFromForces(const Model& model,
                                               std::shared_ptr<const HeldMassless> held)
    : model_(model), constant_mass_(!model.is_nonlinear()), held_(std::move(held)) {}

void AccelerationFromForces::factor(const Eigen::SparseMatrix<double>& mass) {
  const Eigen::Index n = mass.rows();
  massless_ = Eigen::VectorXd::Zero(n);
  constrained_.clear();
  std::vector<bool> held(static_cast<std::size_t>(n), false);
  if (held_) {
    for (int h : held_->dofs()) held[static_cast<std::size_t>(h)] = true;
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (mass.coeff(i, i) == 0.0) {
      massless_[i] = 1.0;
      if (!held[static_cast<std::size_t>(i)]) constrained_.push_back(static_cast<int>(i));
    }
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

/// A_Z a_Z = γ − A_rest a_rest in the least-squares sense, by the normal equations A_Zᵀ A_Z
/// (|Z| x |Z|, sparse, as large as the massless constrained DOFs). Rows on massless DOFs alone
/// (supports, drives, ties between massless DOFs) are used alone when they fix a_Z: then a_Z is
/// exact (a support's acceleration is 0, a drive's its second derivative). Otherwise every row
/// is, and the rows that also hold massive DOFs bring their accelerations' error (the run's
/// tolerance) into a_Z.
void AccelerationFromForces::constrained_massless(MechanicalSystem& system, double t,
                                                  const Eigen::VectorXd& u,
                                                  const Eigen::VectorXd& v, Eigen::VectorXd& a) {
  const Eigen::SparseMatrix<double>& A = system.constraint_jacobian(t, u);
  Eigen::VectorXd gamma(A.rows());
  system.acceleration_bias(t, u, v, gamma);
  const Eigen::VectorXd r = gamma - A * a;  // a_Z = 0 here
  // A_Z and its normal equations once for a constant A, at every row otherwise.
  if (!normal_factored_ || !constant_mass_) {
    std::vector<bool> pure(static_cast<std::size_t>(A.rows()), true);
    for (int j = 0; j < static_cast<int>(A.cols()); ++j) {
      if (massless_[j] != 0.0) continue;
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
        if (it.value() != 0.0) pure[static_cast<std::size_t>(it.row())] = false;
      }
    }
    const auto columns = [&](bool pure_only) {
      std::vector<Eigen::Triplet<double>> trip;
      for (std::size_t k = 0; k < constrained_.size(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, constrained_[k]); it; ++it) {
          if (!pure_only || pure[static_cast<std::size_t>(it.row())])
            trip.emplace_back(static_cast<int>(it.row()), static_cast<int>(k), it.value());
        }
      }
      Eigen::SparseMatrix<double> AZ(A.rows(), static_cast<Eigen::Index>(constrained_.size()));
      AZ.setFromTriplets(trip.begin(), trip.end());
      return AZ;
    };
    const auto regular = [&](const Eigen::SparseMatrix<double>& AZ) {
      normal_.compute(Eigen::SparseMatrix<double>(AZ.transpose() * AZ));
      if (normal_.info() != Eigen::Success) return false;
      const Eigen::VectorXd d = normal_.vectorD().cwiseAbs();
      return d.size() == 0 || d.minCoeff() > 1e-12 * d.maxCoeff();
    };
    az_ = columns(true);
    if (!regular(az_)) {
      az_ = columns(false);
      if (!regular(az_))
        throw std::runtime_error("accelerations: the constraints do not fix the massless DOFs");
    }
    normal_factored_ = true;
  }
  const Eigen::VectorXd aZ = normal_.solve(az_.transpose() * r);
  for (std::size_t k = 0; k < constrained_.size(); ++k)
    a[constrained_[k]] = aZ[static_cast<Eigen::Index>(k)];
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
  Eigen::VectorXd a = ldlt_.solve(rhs);  // 0 on the massless DOFs
  if (!constrained_.empty()) constrained_massless(system, t, u, v, a);
  if (held_) {
    held_->accelerations(v, model_.applied_forces_derivative(1, t),
                         model_.applied_forces_derivative(2, t), a);
  }
  return a;
}

}  // namespace condyn
