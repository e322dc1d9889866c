// The projection scheme's Newton systems as one sparse saddle-point solve
// (dae/formulations/kkt_newton.hpp), factored by KLU with its analysis kept
// (dae/linsolve/fixed_pattern_klu.hpp): the pattern of M + γC + γ²K does not depend on γ.

#include "dae/formulations/kkt_newton.hpp"

#include <stdexcept>
#include <utility>

#include "dae/linsolve/kkt.hpp"

namespace condyn {

KktNewton::KktNewton(LinearMatrices&& matrices, std::shared_ptr<const HeldMassless> held)
    : held_(std::move(held)) {
  // Eigen 3.4's SparseMatrix has no move constructor: swapped in, not copied.
  M_.swap(matrices.M);
  C_.swap(matrices.C);
  K_.swap(matrices.K);
  A_.swap(matrices.A);
  n_ = static_cast<int>(M_.rows());
  m_ = static_cast<int>(A_.rows());
  work_.resize(n_ + m_);
  if (M_.cols() != n_ || K_.rows() != n_ || K_.cols() != n_ || (m_ > 0 && A_.cols() != n_) ||
      (C_.size() > 0 && (C_.rows() != n_ || C_.cols() != n_))) {
    throw std::invalid_argument("KktNewton: the sizes of M, C, K and A disagree");
  }
  if (C_.size() == 0) C_.resize(n_, n_);
  const Eigen::SparseMatrix<double> first = saddle(1.0);
  nonzeros_ = first.nonZeros();
}

Eigen::SparseMatrix<double> KktNewton::saddle(double gamma) const {
  // M + γC + γ²K keeps the union of the three patterns whatever γ (no pruning): one analysis.
  const Eigen::SparseMatrix<double> S = M_ + gamma * C_ + (gamma * gamma) * K_;
  return m_ > 0 ? kkt_matrix(S, A_) : S;
}

bool KktNewton::setup(double gamma) {
  gamma_ = gamma;
  return klu_.factor(saddle(gamma));
}

void KktNewton::solve(Eigen::Ref<Eigen::VectorXd> b) {
  const auto bu = b.head(n_);
  const auto bv = b.segment(n_, n_);
  // One buffer for the right-hand side and the solution, sized once: no allocation per solve.
  Eigen::VectorXd& x = work_;
  x.head(n_).noalias() = M_ * bv;
  x.head(n_).noalias() -= gamma_ * (K_ * bu);
  if (m_ > 0) x.tail(m_).noalias() = A_ * bv;
  if (held_) {  // their rows differentiated (kkt_newton.hpp)
    const Eigen::VectorXd kv = K_ * bv;
    for (int h : held_->undamped()) x[h] = gamma_ * gamma_ * kv[h];
    if (!held_->damped().empty()) {
      const Eigen::VectorXd cv = C_ * bv;
      for (int h : held_->damped()) x[h] = gamma_ * cv[h];
    }
  }
  klu_.solve_in_place(x);
  const auto xv = x.head(n_);
  b.head(n_) += gamma_ * xv;  // x_u = b_u + γ x_v
  b.segment(n_, n_) = xv;
}

}  // namespace condyn
