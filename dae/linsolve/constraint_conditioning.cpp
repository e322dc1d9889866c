#include "dae/linsolve/constraint_conditioning.hpp"

#include <algorithm>
#include <cmath>

namespace condyn {

ConstraintConditioning::ConstraintConditioning(const MechanicalSystem& system)
    : system_(system.clone()) {}

void ConstraintConditioning::weigh(double t, const Eigen::VectorXd& u) {
  const Eigen::SparseMatrix<double>& mass = system_->mass(t, u);
  weight_.resize(mass.rows());
  // A massless column (a support's DOF) weighs as the lightest massive one: its rows then count
  // as rows on a mass of that size, which keeps them in the measure without an infinite weight.
  double lightest = 0.0;
  for (Eigen::Index j = 0; j < mass.rows(); ++j) {
    weight_[j] = mass.coeff(j, j);
    if (weight_[j] > 0.0 && (lightest == 0.0 || weight_[j] < lightest)) lightest = weight_[j];
  }
  if (lightest == 0.0) lightest = 1.0;
  for (double& w : weight_) w = 1.0 / std::sqrt(w > 0.0 ? w : lightest);
}

bool ConstraintConditioning::factor_gram() {
  const Eigen::SparseMatrix<double>& A = *rows_;
  const Eigen::Index m = A.rows();
  if (m <= kDenseRows) {
    // (A W)(A W)ᵀ column by column into a dense m x m: no allocation at small m, where a sparse
    // product and factorization cost more than the step the monitor watches.
    dense_gram_.setZero(m, m);
    for (int j = 0; j < A.outerSize(); ++j) {
      const double w2 = weight_[j] * weight_[j];
      for (Eigen::SparseMatrix<double>::InnerIterator a(A, j); a; ++a) {
        for (Eigen::SparseMatrix<double>::InnerIterator b(A, j); b; ++b) {
          dense_gram_(a.row(), b.row()) += a.value() * b.value() * w2;
        }
      }
    }
    norms_ = dense_gram_.diagonal();
  } else {
    scaled_ = A * weight_.asDiagonal();
    sparse_gram_ = scaled_ * scaled_.transpose();
    norms_ = sparse_gram_.diagonal();
  }
  // An empty row (a velocity row with no coefficient here) stays empty and makes the Gram matrix
  // singular: it holds nothing at this configuration, which is what a singular one means.
  for (double& n : norms_) n = n > 0.0 ? 1.0 / std::sqrt(n) : 1.0;
  if (m <= kDenseRows) {
    dense_gram_ = norms_.asDiagonal() * dense_gram_ * norms_.asDiagonal();
    dense_.compute(dense_gram_);
    return dense_.info() == Eigen::Success;
  }
  sparse_gram_ = norms_.asDiagonal() * sparse_gram_ * norms_.asDiagonal();
  if (!analysed_ || sparse_gram_.nonZeros() != gram_nonzeros_) {
    sparse_.analyzePattern(sparse_gram_);
    gram_nonzeros_ = sparse_gram_.nonZeros();
    analysed_ = true;
  }
  sparse_.factorize(sparse_gram_);
  return sparse_.info() == Eigen::Success && (sparse_.vectorD().array() > 0.0).all();
}

Eigen::VectorXd ConstraintConditioning::solve(const Eigen::VectorXd& x) const {
  return rows_->rows() <= kDenseRows ? Eigen::VectorXd(dense_.solve(x))
                                     : Eigen::VectorXd(sparse_.solve(x));
}

double ConstraintConditioning::operator()(double t, const Eigen::VectorXd& u) {
  if (rows_ != nullptr && t == last_t_ && u.size() == last_u_.size() && u == last_u_) {
    return last_sigma_;
  }
  last_t_ = t;
  last_u_ = u;
  last_sigma_ = sigma_min(t, u);
  return last_sigma_;
}

double ConstraintConditioning::sigma_min(double t, const Eigen::VectorXd& u) {
  rows_ = &system_->constraint_jacobian(t, u);  // valid until this clone's next call
  weigh(t, u);
  factored_ = factor_gram();
  if (!factored_) return 0.0;
  const Eigen::Index m = rows_->rows();
  if (start_.size() != m) {
    // No zero components: a start orthogonal to the smallest singular vector would miss it.
    start_ = Eigen::VectorXd::LinSpaced(m, 1.0, 2.0).normalized();
  }
  // Inverse iteration; the Rayleigh quotient ‖Âᵀx‖² bounds λ_min(Â Âᵀ) = σ_min² from above.
  constexpr int kIterations = 3;
  Eigen::VectorXd x = start_;
  for (int k = 0; k < kIterations; ++k) {
    x = solve(x);
    const double size = x.norm();
    if (!std::isfinite(size) || size == 0.0) return 0.0;
    x /= size;
  }
  start_ = x;
  // Âᵀx = W Aᵀ N x.
  return (weight_.asDiagonal() * (rows_->transpose() * norms_.cwiseProduct(x))).norm();
}

double ConstraintConditioning::forbidden_share(const Eigen::VectorXd& v) const {
  if (!factored_) return -1.0;
  const Eigen::VectorXd p = v.cwiseQuotient(weight_);
  const double energy = p.squaredNorm();
  if (!(energy > 0.0)) return -1.0;
  // ‖P p‖² = (Â p)ᵀ (Â Âᵀ)⁻¹ (Â p), Â p = N A v.
  const Eigen::VectorXd ap = norms_.cwiseProduct(*rows_ * v);
  return std::clamp(ap.dot(solve(ap)) / energy, 0.0, 1.0);
}

}  // namespace condyn
