#include "dae/linsolve/block_jacobian.hpp"

#include <algorithm>
#include <stdexcept>

namespace condyn {

void BlockJacobian::declare(int row0, int col0, const Sparse& S) {
  Block b{row0, col0, {}, {}};
  b.starts.reserve(static_cast<std::size_t>(S.outerSize()) + 1);
  b.rows.reserve(static_cast<std::size_t>(S.nonZeros()));
  for (int k = 0; k < S.outerSize(); ++k) {
    b.starts.push_back(static_cast<int>(b.rows.size()));
    for (Sparse::InnerIterator it(S, k); it; ++it) b.rows.push_back(static_cast<int>(it.row()));
  }
  b.starts.push_back(static_cast<int>(b.rows.size()));
  blocks_.push_back(std::move(b));
}

void BlockJacobian::declare_identity(int row0, int col0, int count) {
  Block b{row0, col0, {}, {}};
  b.starts.resize(static_cast<std::size_t>(count) + 1);
  b.rows.resize(static_cast<std::size_t>(count));
  for (int k = 0; k <= count; ++k) b.starts[static_cast<std::size_t>(k)] = k;
  for (int k = 0; k < count; ++k) b.rows[static_cast<std::size_t>(k)] = k;
  blocks_.push_back(std::move(b));
}

void BlockJacobian::finish() {
  declare_identity(0, 0, size_);
  const auto n = static_cast<std::size_t>(size_);
  // Column by column: every block's rows in that column, shifted, then sorted without repeats.
  std::vector<long> start(n + 1, 0);
  for (const Block& b : blocks_) {
    const int cols = static_cast<int>(b.starts.size()) - 1;
    if (b.col0 < 0 || b.col0 + cols > size_) {
      throw std::logic_error("BlockJacobian: a block's columns run outside the matrix");
    }
    for (int k = 0; k < cols; ++k) {
      start[static_cast<std::size_t>(b.col0 + k) + 1] +=
          b.starts[static_cast<std::size_t>(k) + 1] - b.starts[static_cast<std::size_t>(k)];
    }
  }
  for (std::size_t j = 0; j < n; ++j) start[j + 1] += start[j];
  std::vector<int> rows(static_cast<std::size_t>(start[n]));
  std::vector<long> fill(start.begin(), start.end() - 1);
  for (const Block& b : blocks_) {
    for (std::size_t k = 0; k + 1 < b.starts.size(); ++k) {
      long& at = fill[static_cast<std::size_t>(b.col0) + k];
      for (int q = b.starts[k]; q < b.starts[k + 1]; ++q) {
        const int row = b.row0 + b.rows[static_cast<std::size_t>(q)];
        if (row < 0 || row >= size_) {
          throw std::logic_error("BlockJacobian: a block's rows run outside the matrix");
        }
        rows[static_cast<std::size_t>(at++)] = row;
      }
    }
  }
  blocks_.clear();
  blocks_.shrink_to_fit();
  std::vector<int> outer(n + 1, 0);
  std::size_t kept = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const auto first = rows.begin() + start[j];
    const auto last = rows.begin() + start[j + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    for (auto it = first; it != end; ++it) rows[kept++] = *it;  // moves left: kept <= start[j]
    outer[j + 1] = static_cast<int>(kept);
  }
  rows.resize(kept);
  rows.shrink_to_fit();
  pattern_ = JacobianPattern{size_, std::move(outer), std::move(rows)};
}

Eigen::SparseMatrix<double> JacobianPattern::matrix() const {
  Eigen::SparseMatrix<double> J(size, size);
  J.resizeNonZeros(nonZeros());
  std::copy(outer.begin(), outer.end(), J.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), J.innerIndexPtr());
  std::fill_n(J.valuePtr(), nonZeros(), 0.0);
  return J;
}

namespace {

double& entry(JacobianMap& J, int row, int col) {
  const auto* begin = J.innerIndexPtr() + J.outerIndexPtr()[col];
  const auto* end = J.innerIndexPtr() + J.outerIndexPtr()[col + 1];
  const auto* it = std::lower_bound(begin, end, row);
  if (it == end || *it != row) {
    throw std::logic_error("BlockJacobian: entry (" + std::to_string(row) + "," +
                           std::to_string(col) + ") is outside the declared pattern");
  }
  return J.valuePtr()[it - J.innerIndexPtr()];
}

}  // namespace

void BlockJacobian::add(JacobianMap& J, int row0, int col0, const Sparse& S, double scale) {
  for (int k = 0; k < S.outerSize(); ++k) {
    for (Sparse::InnerIterator it(S, k); it; ++it) {
      entry(J, row0 + static_cast<int>(it.row()), col0 + static_cast<int>(it.col())) +=
          scale * it.value();
    }
  }
}

void BlockJacobian::add_identity(JacobianMap& J, int row0, int col0, int count, double scale) {
  for (int k = 0; k < count; ++k) entry(J, row0 + k, col0 + k) += scale;
}

}  // namespace condyn
