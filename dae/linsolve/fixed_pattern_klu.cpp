// KLU with its analysis and pivots kept across factorizations (dae/linsolve/fixed_pattern_klu.hpp).

#include "dae/linsolve/fixed_pattern_klu.hpp"

#include <klu.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dae/linsolve/band_ordering.hpp"
#include "dae/linsolve/klu_streamed_solve.hpp"

namespace condyn {

struct FixedPatternKlu::Impl {
  klu_common common{};
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  int n = 0;
  /// The factors copied for the streamed solve, when large enough (KluSettings).
  std::optional<KluStreamedSolve> streamed;

  Impl() { klu_defaults(&common); }
  ~Impl() {
    if (numeric != nullptr) klu_free_numeric(&numeric, &common);
    if (symbolic != nullptr) klu_free_symbolic(&symbolic, &common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
};

FixedPatternKlu::FixedPatternKlu(KluSettings settings)
    : impl_(std::make_unique<Impl>()), settings_(settings) {
  impl_->common.ordering = settings.ordering;
}

void FixedPatternKlu::restart() {
  Impl& k = *impl_;
  k.streamed.reset();
  if (k.numeric != nullptr) klu_free_numeric(&k.numeric, &k.common);
}
FixedPatternKlu::~FixedPatternKlu() = default;

bool FixedPatternKlu::factor(const Eigen::SparseMatrix<double>& matrix) {
  if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
    throw std::invalid_argument("FixedPatternKlu: a square compressed matrix is expected");
  }
  return factor(static_cast<int>(matrix.rows()), matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                matrix.valuePtr());
}

bool FixedPatternKlu::factor(const Eigen::Map<Eigen::SparseMatrix<double>>& matrix) {
  if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
    throw std::invalid_argument("FixedPatternKlu: a square compressed matrix is expected");
  }
  return factor(static_cast<int>(matrix.rows()), matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                matrix.valuePtr());
}

bool FixedPatternKlu::factor(int n, const int* outer, const int* inner, const double* values) {
  Impl& k = *impl_;
  // KLU's interface takes non-const arrays it does not write.
  auto* p = const_cast<int*>(outer);
  auto* i = const_cast<int*>(inner);
  auto* x = const_cast<double*>(values);
  if (k.symbolic == nullptr) return first_factor(n, p, i, x);
  if (n != k.n) {
    throw std::invalid_argument("FixedPatternKlu: the matrix changed size");
  }
  if (k.numeric != nullptr) {
    // The tolerance SUNDIALS' SUNLinSol_KLU applies to its refactorizations.
    static const double kMinRcond = std::pow(std::numeric_limits<double>::epsilon(), 2.0 / 3.0);
    if (klu_refactor(p, i, x, k.symbolic, k.numeric, &k.common) != 0 &&
        klu_rcond(k.symbolic, k.numeric, &k.common) != 0) {
      const bool keep = k.common.rcond >= kMinRcond ||
                        (settings_.confirm_with_condest &&
                         klu_condest(p, x, k.symbolic, k.numeric, &k.common) != 0 &&
                         k.common.condest <= 1.0 / kMinRcond);
      if (keep) {
        ++refactored_;
        if (k.streamed) k.streamed->refresh_values(*k.symbolic, *k.numeric);
        return true;
      }
    }
    klu_free_numeric(&k.numeric, &k.common);
  }
  k.streamed.reset();  // before the new factors are allocated
  ++pivoting_;
  k.numeric = klu_factor(p, i, x, k.symbolic, &k.common);
  return copy_for_streamed_solve();
}

KluFactorPrediction predicted_klu_factor(const Eigen::SparseMatrix<double>& matrix) {
  if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
    throw std::invalid_argument("predicted_klu_factor: a square compressed matrix is expected");
  }
  klu_common common{};
  klu_defaults(&common);
  common.ordering = 0;  // AMD, whose analysis counts the factor (COLAMD's does not)
  // KLU's interface takes non-const arrays it does not write.
  klu_symbolic* symbolic =
      klu_analyze(static_cast<int>(matrix.rows()), const_cast<int*>(matrix.outerIndexPtr()),
                  const_cast<int*>(matrix.innerIndexPtr()), &common);
  if (symbolic == nullptr) {
    throw std::runtime_error("KLU's analysis failed (status " + std::to_string(common.status) +
                             ")");
  }
  const KluFactorPrediction prediction{symbolic->lnz + symbolic->unz + symbolic->nzoff,
                                       std::max(symbolic->est_flops, 0.0)};
  klu_free_symbolic(&symbolic, &common);
  return prediction;
}

bool FixedPatternKlu::streamed() const { return impl_->streamed.has_value(); }

bool FixedPatternKlu::copy_for_streamed_solve() {
  Impl& k = *impl_;
  k.streamed.reset();
  if (k.numeric == nullptr || k.common.status != KLU_OK) return false;
  const double entries = static_cast<double>(k.numeric->lnz) + k.numeric->unz;
  const auto from = static_cast<double>(settings_.streamed_solve_from);
  // KLU's count of this factorization's flops (the pivots it chose determine it), taken for
  // large factors alone: it reads the whole factor.
  if (entries >= from && klu_flops(k.symbolic, k.numeric, &k.common) != 0 &&
      keeps_streamed_copy(entries, k.common.flops, from,
                          settings_.streamed_solve_most_flops_per_entry)) {
    try {
      k.streamed.emplace();
      k.streamed->build(*k.symbolic, *k.numeric);
    } catch (const std::bad_alloc&) {
      k.streamed.reset();  // no room for the copy: klu_solve on KLU's own factors, slower
    }
  }
  return true;
}

namespace {

/// The factor's entries: L's and U's, diagonals included, and those of the blocks off the
/// diagonal of KLU's block triangular form.
long factor_entries(const klu_numeric& numeric) {
  return numeric.lnz + numeric.unz + numeric.nzoff;
}

}  // namespace

bool FixedPatternKlu::first_factor(int n, int* p, int* i, double* x) {
  Impl& k = *impl_;
  k.n = n;
  k.symbolic = klu_analyze(k.n, p, i, &k.common);
  if (k.symbolic == nullptr) return false;
  ++pivoting_;
  k.numeric = klu_factor(p, i, x, k.symbolic, &k.common);
  if (k.numeric == nullptr || k.common.status != KLU_OK) return false;
  if (n < settings_.band_ordering_from) return copy_for_streamed_solve();

  // The band ordering is tried when the factor of A + Aᵀ under it, an upper bound on A's LU
  // factors when KLU pivots on the diagonal (as it prefers to), has at most 2.5 times as many
  // entries as this factor: on IDA's Newton matrices, whose rows u' - v pair each position with
  // its velocity alone, the bound is twice the LU factor's count (the benchmark lattice's
  // index-1 and GGL matrices: 2.02 times). It is kept when its factor has no more entries than
  // this one. This factor is freed first: a trial that loses holds at most 2.5 times its memory
  // for one factorization.
  const long entries = factor_entries(*k.numeric);
  klu_free_numeric(&k.numeric, &k.common);
  std::vector<int> order;
  {
    const SymmetricPattern pattern = symmetric_pattern(n, p, i);
    order = reverse_cuthill_mckee(pattern);
    // Below the diagonal, of at most 2.5 · entries in all with both diagonals.
    const long below_limit = (5 * (entries / 2) - 2L * n) / 2;
    if (cholesky_entries_below_diagonal(pattern, order, below_limit) > below_limit) order.clear();
  }
  klu_symbolic* band =
      order.empty() ? nullptr : klu_analyze_given(n, p, i, order.data(), order.data(), &k.common);
  if (band != nullptr) {
    klu_numeric* numeric = klu_factor(p, i, x, band, &k.common);
    if (numeric != nullptr && k.common.status == KLU_OK && factor_entries(*numeric) <= entries) {
      klu_free_symbolic(&k.symbolic, &k.common);
      k.symbolic = band;
      k.numeric = numeric;
      band_ordered_ = true;
      return copy_for_streamed_solve();
    }
    if (numeric != nullptr) klu_free_numeric(&numeric, &k.common);
    klu_free_symbolic(&band, &k.common);
  }
  k.numeric = klu_factor(p, i, x, k.symbolic, &k.common);
  return copy_for_streamed_solve();
}

void FixedPatternKlu::solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const {
  Impl& k = *impl_;
  if (k.numeric == nullptr) throw std::logic_error("FixedPatternKlu: solve before a factorization");
  if (x.size() != k.n)
    throw std::invalid_argument("FixedPatternKlu: right-hand side of wrong size");
  if (k.streamed) {
    k.streamed->solve(*k.symbolic, *k.numeric, x);
    return;
  }
  if (klu_solve(k.symbolic, k.numeric, k.n, 1, x.data(), &k.common) == 0) {
    throw std::runtime_error("KLU solve failed (status " + std::to_string(k.common.status) + ")");
  }
}

Eigen::VectorXd FixedPatternKlu::solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd x = rhs;
  solve_in_place(x);
  return x;
}

bool KluByPattern::factor(const Eigen::SparseMatrix<double>& matrix) {
  Eigen::SparseMatrix<double> compressed;
  if (!matrix.isCompressed()) {
    compressed = matrix;
    compressed.makeCompressed();
  }
  const Eigen::SparseMatrix<double>& a = matrix.isCompressed() ? matrix : compressed;
  const auto* outer = a.outerIndexPtr();
  const auto* inner = a.innerIndexPtr();
  const auto n = static_cast<std::size_t>(a.cols());
  const auto nnz = static_cast<std::size_t>(a.nonZeros());
  const bool same = klu_ && outer_.size() == n + 1 && inner_.size() == nnz &&
                    std::equal(outer_.begin(), outer_.end(), outer) &&
                    std::equal(inner_.begin(), inner_.end(), inner);
  if (!same) {
    klu_ = std::make_unique<FixedPatternKlu>();
    outer_.assign(outer, outer + n + 1);
    inner_.assign(inner, inner + nnz);
    ++analyses_;
  } else {
    klu_->restart();  // pivots afresh: the analysis alone is kept
  }
  factored_ = klu_->factor(a);
  return factored_;
}

Eigen::VectorXd KluByPattern::solve(const Eigen::VectorXd& rhs) const {
  if (!factored_) throw std::logic_error("KluByPattern: solve without a factorization");
  return klu_->solve(rhs);
}

}  // namespace condyn
