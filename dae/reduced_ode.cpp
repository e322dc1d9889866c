#include "dae/reduced_ode.hpp"

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
  std::vector<Eigen::Triplet<double>> j0, j1;
  for (int k = 0; k < nm_; ++k) {
    j1.emplace_back(k, k, 1.0);         // dF1/dû'
    j0.emplace_back(k, nm_ + k, -1.0);  // dF1/dw
  }
  auto add = [](std::vector<Eigen::Triplet<double>>& out, const Eigen::SparseMatrix<double>& s,
                int row0, int col0) {
    for (int k = 0; k < s.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(s, k); it; ++it) {
        out.emplace_back(row0 + static_cast<int>(it.row()), col0 + static_cast<int>(it.col()),
                         it.value());
      }
    }
  };
  add(j0, reduced.K, nm_, 0);
  add(j0, reduced.C, nm_, nm_);
  add(j1, reduced.M, nm_, nm_);
  const int n = size();
  Eigen::SparseMatrix<double> J0(n, n), J1(n, n);
  J0.setFromTriplets(j0.begin(), j0.end());
  J1.setFromTriplets(j1.begin(), j1.end());
  jacobian_ = AffineJacobian(J0, J1);
}

void ReducedOde::residual(double t, double step_reference, ConstRef y, ConstRef yp, Ref r) const {
  const auto x = y.head(nm_), w = y.tail(nm_);
  r.head(nm_) = yp.head(nm_) - w;
  r.tail(nm_) =
      reduced_.M * yp.tail(nm_) + reduced_.K * x - reduced_.forces(model_, t, step_reference);
  if (model_.has_damping()) r.tail(nm_) += reduced_.C * w;
}

void ReducedOde::jacobian(double /*t*/, double /*step_reference*/, ConstRef /*y*/, ConstRef /*yp*/,
                          double cj, Eigen::SparseMatrix<double>& J) const {
  jacobian_.fill(cj, J);
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

}  // namespace condyn
