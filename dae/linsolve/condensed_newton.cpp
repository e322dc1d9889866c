// IDA's index1 and GGL Newton systems condensed to [u; λ (; μ)]
// (dae/linsolve/condensed_newton.hpp).

#include "dae/linsolve/condensed_newton.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace condyn {

CondensedNewton::CondensedNewton(Scheme scheme, LinearMatrices&& matrices, const Sparse& select_p)
    : scheme_(scheme),
      n_(static_cast<int>(matrices.M.rows())),
      m_(static_cast<int>(matrices.A.rows())),
      p_(scheme == Scheme::ggl ? static_cast<int>(select_p.rows()) : 0),
      klu_(KluSettings{.ordering = m_ + p_ > 0 ? 1 : 0}) {
  // Taken over by swaps: Eigen 3.4's sparse matrices have no move constructor.
  M_.swap(matrices.M);
  C_.swap(matrices.C);
  K_.swap(matrices.K);
  A_.swap(matrices.A);
  if (scheme != Scheme::index1 && scheme != Scheme::ggl) {
    throw std::invalid_argument("CondensedNewton: index1 or ggl only");
  }
  if (K_.size() == 0) K_.resize(n_, n_);
  if (C_.size() == 0) C_.resize(n_, n_);
  if (m_ == 0) A_.resize(0, n_);
  for (Sparse* x : {&M_, &C_, &K_, &A_}) x->makeCompressed();
  At_ = A_.transpose();
  if (p_ > 0) {
    Ap_ = select_p * A_;
    ApT_ = Ap_.transpose();
    CApT_ = C_ * ApT_;
    MApT_ = M_ * ApT_;
    AApT_ = A_ * ApT_;
  }
  // The union of every block's pattern, whatever cj (no cancellation can drop an entry).
  BlockJacobian blocks(n_ + m_ + p_);
  for (const Sparse* x : {&K_, &C_, &M_}) blocks.declare(0, 0, *x);
  blocks.declare(0, n_, At_);
  blocks.declare(n_, 0, A_);
  if (p_ > 0) {
    blocks.declare(0, n_ + m_, CApT_);
    blocks.declare(0, n_ + m_, MApT_);
    blocks.declare(n_, n_ + m_, AApT_);
    blocks.declare(n_ + m_, 0, Ap_);
  }
  blocks.finish();
  matrix_ = blocks.pattern().matrix();
  diagonals_ = {K_.diagonal(), C_.diagonal(), M_.diagonal()};
  largest_a_ = A_.nonZeros() > 0 ? A_.coeffs().cwiseAbs().maxCoeff() : 0.0;
  rhs_.resize(n_ + m_ + p_);
  r1_.resize(n_);
  work_.resize(n_);
  if (static_cast<double>(M_.nonZeros() + C_.nonZeros()) >= kLanedProductFewestEntries) {
    products_ = std::make_unique<SymmetricProducts>(
        std::vector<const Eigen::SparseMatrix<double>*>{&M_, &C_});
  }
}

namespace {

/// The power of two nearest below a positive finite x; 1 for any other.
double power_of_two_below(double x) {
  return x > 0.0 && std::isfinite(x) ? std::ldexp(1.0, std::ilogb(x)) : 1.0;
}

}  // namespace

CondensedNewton::Scales CondensedNewton::scales(double cj) const {
  if (largest_a_ == 0.0) return {};
  const auto& [k, c, m] = diagonals_;
  const double d = (k + cj * c + cj * cj * m).cwiseAbs().maxCoeff();
  if (!(d > 0.0)) return {};
  const double lambda = d / largest_a_;
  if (scheme_ == Scheme::index1) return {power_of_two_below(lambda), 1.0};
  const double e = std::max((c + cj * m).cwiseAbs().maxCoeff(), d / cj);
  return {power_of_two_below(lambda), power_of_two_below(lambda / e)};
}

bool CondensedNewton::setup(double cj) {
  cj_ = cj;
  scale_ = scales(cj);
  const Scales& s = scale_;
  JacobianMap J = map_of(matrix_);
  std::fill_n(J.valuePtr(), J.nonZeros(), 0.0);
  BlockJacobian::add(J, 0, 0, K_);
  BlockJacobian::add(J, 0, 0, C_, cj);
  BlockJacobian::add(J, 0, 0, M_, cj * cj);
  BlockJacobian::add(J, 0, n_, At_, s.lambda);
  BlockJacobian::add(J, n_, 0, A_, scheme_ == Scheme::index1 ? 1.0 : cj);
  if (p_ > 0) {
    BlockJacobian::add(J, 0, n_ + m_, CApT_, s.mu);
    BlockJacobian::add(J, 0, n_ + m_, MApT_, s.mu * cj);
    BlockJacobian::add(J, n_, n_ + m_, AApT_, s.mu);
    BlockJacobian::add(J, n_ + m_, 0, Ap_);
  }
  return cholmod_ ? cholmod_->factor(matrix_) : klu_.factor(matrix_);
}

bool CondensedNewton::use_cholmod(const std::string& ordering) {
  if (symmetric_matrix() == nullptr) return false;
  cholmod_ = std::make_unique<FixedPatternCholmod>(ordering);
  return true;
}

void CondensedNewton::solve(Eigen::Ref<Eigen::VectorXd> b) {
  const double cj = cj_;
  const Eigen::Index n = n_, m = m_, p = p_;
  r1_ = b.segment(0, n);
  auto top = rhs_.head(n);
  if (products_) {
    const std::array<ProductInput, 2> inputs{ProductInput{r1_.data(), cj},
                                             ProductInput{r1_.data()}};
    products_->apply(inputs, top.data());
  } else {
    top.noalias() = M_ * r1_;
    top *= cj;
    top.noalias() += C_ * r1_;  // (C + cj M) r1
  }
  top += b.segment(n, n);
  if (m > 0) {
    auto mid = rhs_.segment(n, m);
    mid.noalias() = A_ * r1_;
    if (scheme_ == Scheme::index1) {
      mid = (b.segment(2 * n, m) + cj * mid) / (cj * cj);
    } else {
      mid += b.segment(2 * n, m);
    }
  }
  if (p > 0) rhs_.tail(p) = b.segment(2 * n + m, p);
  if (cholmod_) {
    cholmod_->solve_in_place(rhs_);
  } else {
    klu_.solve_in_place(rhs_);
  }
  const auto du = rhs_.head(n);
  auto dv = b.segment(n, n);
  dv = cj * du - r1_;
  if (p > 0) {
    rhs_.tail(p) *= scale_.mu;  // dμ
    work_.noalias() = ApT_ * rhs_.tail(p);
    dv += work_;
  }
  b.segment(0, n) = du;
  if (m > 0) b.segment(2 * n, m) = scale_.lambda * rhs_.segment(n, m);
  if (p > 0) b.segment(2 * n + m, p) = rhs_.tail(p);
}

}  // namespace condyn
