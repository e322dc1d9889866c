#include "dae/block_jacobian.hpp"

#include <algorithm>
#include <stdexcept>

namespace condyn {

void BlockJacobian::declare(int row0, int col0, const Sparse& S) {
  for (int k = 0; k < S.outerSize(); ++k) {
    for (Sparse::InnerIterator it(S, k); it; ++it) {
      marks_.emplace_back(row0 + static_cast<int>(it.row()), col0 + static_cast<int>(it.col()),
                          1.0);
    }
  }
}

void BlockJacobian::declare_identity(int row0, int col0, int count) {
  for (int k = 0; k < count; ++k) marks_.emplace_back(row0 + k, col0 + k, 1.0);
}

void BlockJacobian::finish() {
  declare_identity(0, 0, size_);
  pattern_.resize(size_, size_);
  pattern_.setFromTriplets(marks_.begin(), marks_.end());
  pattern_.makeCompressed();
  std::fill_n(pattern_.valuePtr(), pattern_.nonZeros(), 0.0);
  marks_.clear();
  marks_.shrink_to_fit();
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
