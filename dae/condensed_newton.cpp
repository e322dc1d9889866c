// IDA's index1 and GGL Newton systems condensed to [u; λ (; μ)] (dae/condensed_newton.hpp).

#include "dae/condensed_newton.hpp"

#include <stdexcept>
#include <vector>

namespace condyn {

CondensedNewton::CondensedNewton(Scheme scheme, const Eigen::SparseMatrix<double>& M,
                                 const Eigen::SparseMatrix<double>& C,
                                 const Eigen::SparseMatrix<double>& K,
                                 const Eigen::SparseMatrix<double>& A,
                                 const Eigen::SparseMatrix<double>& select_p)
    : scheme_(scheme),
      M_(M),
      C_(C),
      K_(K),
      A_(A),
      n_(static_cast<int>(M_.rows())),
      m_(static_cast<int>(A_.rows())),
      p_(scheme == Scheme::ggl ? static_cast<int>(select_p.rows()) : 0) {
  if (scheme != Scheme::index1 && scheme != Scheme::ggl) {
    throw std::invalid_argument("CondensedNewton: index1 or ggl only");
  }
  if (C_.size() == 0) C_.resize(n_, n_);
  if (m_ == 0) A_.resize(0, n_);
  if (p_ > 0) {
    Ap_ = select_p * A_;
    ApT_ = Ap_.transpose();
    AApT_ = A_ * ApT_;
  }
  // The union of every block's pattern: the entries of the magnitudes' sum cannot cancel.
  pattern_ = matrix(1.0, true);
  std::fill_n(pattern_.valuePtr(), pattern_.nonZeros(), 0.0);
}

Eigen::SparseMatrix<double> CondensedNewton::matrix(double cj, bool magnitudes) const {
  const auto abs = [magnitudes](const Eigen::SparseMatrix<double>& x) {
    return magnitudes ? Eigen::SparseMatrix<double>(x.cwiseAbs()) : x;
  };
  const Eigen::SparseMatrix<double> S = abs(K_) + cj * abs(C_) + (cj * cj) * abs(M_);
  const int size = n_ + m_ + p_;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(S.nonZeros() + 2 * A_.nonZeros() + 2 * Ap_.nonZeros()));
  const auto place = [&t](const Eigen::SparseMatrix<double>& x, int r0, int c0, double s) {
    for (int k = 0; k < x.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(x, k); it; ++it) {
        t.emplace_back(r0 + static_cast<int>(it.row()), c0 + static_cast<int>(it.col()),
                       s * it.value());
      }
    }
  };
  const Eigen::SparseMatrix<double> a = abs(A_);
  const Eigen::SparseMatrix<double> at = a.transpose();
  place(S, 0, 0, 1.0);
  place(at, 0, n_, 1.0);
  if (scheme_ == Scheme::index1) {
    place(a, n_, 0, 1.0);
  } else {
    place(a, n_, 0, cj);
    if (p_ > 0) {
      const Eigen::SparseMatrix<double> damping = abs(C_) + cj * abs(M_);
      place(Eigen::SparseMatrix<double>(damping * abs(ApT_)), 0, n_ + m_, 1.0);
      place(abs(AApT_), n_, n_ + m_, 1.0);
      place(abs(Ap_), n_ + m_, 0, 1.0);
    }
  }
  Eigen::SparseMatrix<double> out(size, size);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

bool CondensedNewton::setup(double cj) {
  cj_ = cj;
  // On the fixed pattern (a superset of this cj's entries): KLU's analysis stays valid.
  return klu_.factor(pattern_ + matrix(cj, false));
}

void CondensedNewton::solve(Eigen::Ref<Eigen::VectorXd> b) {
  const double cj = cj_;
  const Eigen::Index n = n_, m = m_, p = p_;
  const Eigen::VectorXd r1 = b.segment(0, n);
  Eigen::VectorXd rhs(n_ + m_ + p_);
  Eigen::VectorXd damped = M_ * r1;
  damped *= cj;
  damped += C_ * r1;  // (C + cj M) r1
  rhs.head(n_) = b.segment(n_, n_) + damped;
  if (m_ > 0) {
    const Eigen::VectorXd ar1 = A_ * r1;
    if (scheme_ == Scheme::index1) {
      rhs.segment(n_, m_) = (b.segment(2 * n, m) + cj * ar1) / (cj * cj);
    } else {
      rhs.segment(n_, m_) = b.segment(2 * n, m) + ar1;
    }
  }
  if (p_ > 0) rhs.tail(p_) = b.segment(2 * n + m, p);
  const Eigen::VectorXd x = klu_.solve(rhs);
  const auto du = x.head(n_);
  Eigen::VectorXd dv = cj * du - r1;
  if (p_ > 0) dv += ApT_ * x.tail(p_);
  b.segment(0, n_) = du;
  b.segment(n_, n_) = dv;
  if (m_ > 0) b.segment(2 * n, m) = x.segment(n_, m_);
  if (p_ > 0) b.segment(2 * n + m, p) = x.tail(p_);
}

}  // namespace condyn
