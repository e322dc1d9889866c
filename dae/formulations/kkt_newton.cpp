// The projection scheme's Newton systems as one sparse saddle-point solve
// (dae/formulations/kkt_newton.hpp), factored by KLU with its analysis kept
// (dae/linsolve/fixed_pattern_klu.hpp): the patterns of M + γC + γ²K and A + γQ + γ²P do not
// depend on γ or on the state.

#include "dae/formulations/kkt_newton.hpp"

#include <initializer_list>
#include <stdexcept>
#include <utility>

#include "dae/linsolve/kkt.hpp"

namespace condyn {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

/// Σ scale_k X_k over the nonempty X_k (an empty, 0 x 0, block is a term that vanishes
/// identically), rows x cols. The pattern is the union of the terms' (no pruning): fixed when
/// theirs are.
Sparse combination(Eigen::Index rows, Eigen::Index cols,
                   std::initializer_list<std::pair<double, const Sparse*>> terms) {
  Sparse sum(rows, cols);
  for (const auto& [scale, X] : terms) {
    if (X->size() == 0) continue;
    if (X->rows() != rows || X->cols() != cols) {
      throw std::invalid_argument("KktNewton: a block's size disagrees with the system's");
    }
    sum += scale * *X;
  }
  sum.makeCompressed();
  return sum;
}

}  // namespace

KktNewton::KktNewton(LinearMatrices&& matrices, std::shared_ptr<const HeldMassless> held)
    : held_(std::move(held)) {
  // Eigen 3.4's SparseMatrix has no move constructor: swapped in, not copied.
  M_.swap(matrices.M);
  C_.swap(matrices.C);
  K_.swap(matrices.K);
  A_.swap(matrices.A);
  finish();
}

KktNewton::KktNewton(MechanicalSystem& system, Accelerations accelerations)
    : system_(&system), accelerations_(std::move(accelerations)) {
  // The patterns, at the zero state (every block's pattern is independent of its arguments).
  const int n = system.dofs(), m = system.constraints();
  const Eigen::VectorXd zero_n = Eigen::VectorXd::Zero(n), zero_m = Eigen::VectorXd::Zero(m);
  assemble(0.0, zero_n, zero_n, zero_n, zero_m);
  finish();
}

void KktNewton::finish() {
  n_ = static_cast<int>(M_.rows());
  m_ = static_cast<int>(A_.rows());
  work_.resize(n_ + m_);
  if (M_.cols() != n_ || K_.rows() != n_ || K_.cols() != n_ || (m_ > 0 && A_.cols() != n_) ||
      (C_.size() > 0 && (C_.rows() != n_ || C_.cols() != n_))) {
    throw std::invalid_argument("KktNewton: the sizes of M, C, K and A disagree");
  }
  if (C_.size() == 0) C_.resize(n_, n_);
  const Sparse first = saddle(1.0);
  nonzeros_ = first.nonZeros();
}

void KktNewton::assemble(double t, const ConstRef& u, const ConstRef& v, const ConstRef& a,
                         const ConstRef& lambda) {
  MechanicalSystem& s = *system_;
  const Eigen::Index n = u.size(), m = lambda.size();
  M_ = s.mass(t, u);
  C_ = s.damping(t, u, v);
  // Each block is used before the next call that may overwrite it (references valid until then).
  const Sparse& stiffness = s.stiffness(t, u, v);
  const Sparse& mass_jacobian = s.mass_jacobian(t, u, a);
  if (m == 0) {
    K_ = combination(n, n, {{1.0, &stiffness}, {1.0, &mass_jacobian}});
    A_.resize(0, n);
    return;
  }
  const Sparse& force_jacobian = s.constraint_force_jacobian(t, u, lambda);
  K_ = combination(n, n, {{1.0, &stiffness}, {1.0, &mass_jacobian}, {1.0, &force_jacobian}});
  A_ = s.constraint_jacobian(t, u);
  const Sparse& product_jacobian = s.constraint_product_jacobian(t, u, a);
  const Sparse& bias_u = s.acceleration_bias_jacobian_u(t, u, v);
  P_ = combination(m, n, {{1.0, &product_jacobian}, {-1.0, &bias_u}});
  Q_ = combination(m, n, {{-1.0, &s.acceleration_bias_jacobian_v(t, u, v)}});
}

void KktNewton::linearize_at(double t, const ConstRef& y) {
  if (system_ == nullptr) return;
  const auto u = y.head(n_), v = y.segment(n_, n_);
  const Eigen::VectorXd x = accelerations_(t, u, v);
  assemble(t, u, v, x.head(n_), x.tail(m_));
}

Sparse KktNewton::saddle(double gamma) const {
  // M + γC + γ²K keeps the union of the three patterns whatever γ (no pruning): one analysis.
  const Sparse S = combination(n_, n_, {{1.0, &M_}, {gamma, &C_}, {gamma * gamma, &K_}});
  if (m_ == 0) return S;
  if (P_.size() == 0 && Q_.size() == 0) return kkt_matrix(S, A_);
  const Sparse B = combination(m_, n_, {{1.0, &A_}, {gamma, &Q_}, {gamma * gamma, &P_}});
  return kkt_matrix(S, A_, B);
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
  if (m_ > 0) {
    x.tail(m_).noalias() = A_ * bv;
    if (P_.size() > 0) x.tail(m_).noalias() -= gamma_ * (P_ * bu);
  }
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
