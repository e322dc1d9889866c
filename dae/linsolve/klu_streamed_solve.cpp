// KLU's solves over its factors copied in reading order (dae/linsolve/klu_streamed_solve.hpp).

#include "dae/linsolve/klu_streamed_solve.hpp"

#include <cstddef>
#include <stdexcept>

namespace condyn {

namespace {

/// Column k of L or U in a block's LUbx: `len` row indices (ints padded to whole doubles), then
/// `len` values; KLU's GET_POINTER.
struct FactorColumn {
  const int* rows;
  const double* values;
  int length;
};

FactorColumn factor_column(const double* lu, const int* start, const int* length, int k) {
  const double* at = lu + start[k];
  const int len = length[k];
  const std::size_t index_units =
      (static_cast<std::size_t>(len) * sizeof(int) + sizeof(double) - 1) / sizeof(double);
  return {reinterpret_cast<const int*>(at), at + index_units, len};
}

}  // namespace

template <class Visit>
void KluStreamedSolve::walk(const klu_symbolic& symbolic, const klu_numeric& numeric, Visit visit) {
  for (int block = numeric.nblocks - 1; block >= 0; --block) {
    const int k1 = symbolic.R[block], k2 = symbolic.R[block + 1];
    if (k2 - k1 == 1) continue;  // a singleton: its U diagonal alone
    const auto* lu = static_cast<const double*>(numeric.LUbx[block]);
    for (int k = k1; k < k2; ++k)
      visit(factor_column(lu, numeric.Lip + k1, numeric.Llen + k1, k - k1));
    for (int k = k2 - 1; k >= k1; --k) {
      visit(factor_column(lu, numeric.Uip + k1, numeric.Ulen + k1, k - k1));
    }
  }
}

void KluStreamedSolve::build(const klu_symbolic& symbolic, const klu_numeric& numeric) {
  lengths_.clear();
  rows_.clear();
  values_.clear();
  std::size_t entries = 0, columns = 0;
  walk(symbolic, numeric, [&](const FactorColumn& c) {
    entries += static_cast<std::size_t>(c.length);
    ++columns;
  });
  lengths_.reserve(columns);
  rows_.reserve(entries);
  values_.reserve(entries);
  walk(symbolic, numeric, [&](const FactorColumn& c) {
    lengths_.push_back(c.length);
    rows_.insert(rows_.end(), c.rows, c.rows + c.length);
    values_.insert(values_.end(), c.values, c.values + c.length);
  });
  work_.assign(static_cast<std::size_t>(symbolic.n), 0.0);
}

void KluStreamedSolve::refresh_values(const klu_symbolic& symbolic, const klu_numeric& numeric) {
  std::size_t at = 0, column = 0;
  walk(symbolic, numeric, [&](const FactorColumn& c) {
    if (column >= lengths_.size() || lengths_[column] != c.length) {
      throw std::logic_error("KluStreamedSolve: the factor's pattern changed on refactorization");
    }
    ++column;
    for (int p = 0; p < c.length; ++p) values_[at++] = c.values[p];
  });
}

void KluStreamedSolve::solve(const klu_symbolic& symbolic, const klu_numeric& numeric,
                             Eigen::Ref<Eigen::VectorXd> b) const {
  // klu_solve with one right-hand side, step for step (klu_solve.c): X = P (R \ b), the blocks
  // from the last (L then U, then the off-diagonal entries' update), b = Q X.
  const int n = symbolic.n;
  double* x = work_.data();
  const int* pivot = numeric.Pnum;
  if (numeric.Rs == nullptr) {
    for (int k = 0; k < n; ++k) x[k] = b[pivot[k]];
  } else {
    for (int k = 0; k < n; ++k) x[k] = b[pivot[k]] / numeric.Rs[k];
  }
  const auto* diagonal = static_cast<const double*>(numeric.Udiag);
  const auto* off_values = static_cast<const double*>(numeric.Offx);
  const int* length = lengths_.data();
  const int* row = rows_.data();
  const double* value = values_.data();
  for (int block = numeric.nblocks - 1; block >= 0; --block) {
    const int k1 = symbolic.R[block], k2 = symbolic.R[block + 1], nk = k2 - k1;
    double* xb = x + k1;
    if (nk == 1) {
      xb[0] /= diagonal[k1];
    } else {
      for (int k = 0; k < nk; ++k) {  // unit lower triangular, forward
        const double xk = xb[k];
        const int len = *length++;
        for (int p = 0; p < len; ++p) xb[row[p]] -= value[p] * xk;
        row += len;
        value += len;
      }
      for (int k = nk - 1; k >= 0; --k) {  // upper triangular, backward
        const double xk = xb[k] / diagonal[k1 + k];
        xb[k] = xk;
        const int len = *length++;
        for (int p = 0; p < len; ++p) xb[row[p]] -= value[p] * xk;
        row += len;
        value += len;
      }
    }
    if (block > 0) {
      for (int k = k1; k < k2; ++k) {
        const double xk = x[k];
        for (int p = numeric.Offp[k]; p < numeric.Offp[k + 1]; ++p) {
          x[numeric.Offi[p]] -= off_values[p] * xk;
        }
      }
    }
  }
  const int* column = symbolic.Q;
  for (int k = 0; k < n; ++k) b[column[k]] = x[k];
}

}  // namespace condyn
