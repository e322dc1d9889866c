#include "dae/reduced_ode.hpp"

#include "dae/condensed_newton.hpp"

#include <algorithm>
#include <stdexcept>

namespace condyn {

ReducedOde::ReducedOde(const Model& model, const ReducedSystem& reduced)
    : model_(model), reduced_(reduced), nm_(static_cast<int>(reduced.M.rows())) {
  mass_.compute(reduced.M);
  bool ok = mass_.info() == Eigen::Success;
  if (ok && nm_ > 0) {
    const Eigen::VectorXd d = mass_.vectorD();
    // Positive definite to roundoff of the largest pivot.
    ok = d.minCoeff() > 1e-14 * d.cwiseAbs().maxCoeff();
  }
  if (!ok) {
    std::string massless;
    for (int k = 0; k < nm_; ++k) {
      if (reduced.M.coeff(k, k) == 0.0) {
        const auto dof = reduced.transform.masters[static_cast<std::size_t>(k)];
        massless += (massless.empty() ? "" : ", ") + model.dof_names[static_cast<std::size_t>(dof)];
      }
    }
    throw std::invalid_argument(
        "the reduced mass matrix is singular" +
        (massless.empty() ? std::string() : " (master DOFs without mass: " + massless + ")") +
        ": the elimination path integrates an ODE and needs mass on every master DOF");
  }
  jacobian_ = BlockJacobian(size());
  jacobian_.declare_identity(0, 0, nm_);
  jacobian_.declare_identity(0, nm_, nm_);
  jacobian_.declare(nm_, 0, reduced.K);
  jacobian_.declare(nm_, nm_, reduced.C);
  jacobian_.declare(nm_, nm_, reduced.M);
  jacobian_.finish();
}

void ReducedOde::residual(double t, ConstRef y, ConstRef yp, Ref r) const {
  const auto x = y.head(nm_), w = y.tail(nm_);
  r.head(nm_) = yp.head(nm_) - w;
  r.tail(nm_) = reduced_.M * yp.tail(nm_) + reduced_.K * x -
                reduced_.forces(model_, t, segment_start_.value_or(t));
  if (model_.has_damping()) r.tail(nm_) += reduced_.C * w;
}

void ReducedOde::jacobian(double /*t*/, ConstRef /*y*/, ConstRef /*yp*/, double cj,
                          Eigen::SparseMatrix<double>& J) const {
  std::fill_n(J.valuePtr(), J.nonZeros(), 0.0);
  BlockJacobian::add_identity(J, 0, 0, nm_, cj);
  BlockJacobian::add_identity(J, 0, nm_, nm_, -1.0);
  BlockJacobian::add(J, nm_, 0, reduced_.K);
  BlockJacobian::add(J, nm_, nm_, reduced_.C);
  BlockJacobian::add(J, nm_, nm_, reduced_.M, cj);
}

void ReducedOde::make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const {
  yp.resize(size());
  yp.head(nm_) = y.tail(nm_);
  yp.tail(nm_) = acceleration(t, y.head(nm_), y.tail(nm_));
}

Eigen::VectorXd ReducedOde::acceleration(double t, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& w) const {
  Eigen::VectorXd rhs = reduced_.forces(model_, t, t) - reduced_.K * x;
  if (model_.has_damping()) rhs -= reduced_.C * w;
  return mass_.solve(rhs);
}

std::unique_ptr<NewtonSystem> ReducedOde::newton_system() const {
  return std::make_unique<CondensedNewton>(Scheme::index1, reduced_.M, reduced_.C, reduced_.K,
                                           Eigen::SparseMatrix<double>(0, nm_),
                                           Eigen::SparseMatrix<double>(0, 0));
}

}  // namespace condyn
