// Sums of sparse products by rows on two lanes (models/core/symmetric_products.hpp).

#include "models/core/symmetric_products.hpp"

#include <stdexcept>

#include "models/core/second_lane.hpp"

namespace condyn {

bool exactly_symmetric(const Eigen::SparseMatrix<double>& a) {
  if (a.rows() != a.cols()) return false;
  const Eigen::SparseMatrix<double> t = a.transpose();
  if (t.nonZeros() != a.nonZeros()) return false;
  for (Eigen::Index j = 0; j <= a.outerSize(); ++j) {
    if (t.outerIndexPtr()[j] != a.outerIndexPtr()[j]) return false;
  }
  for (Eigen::Index p = 0; p < a.nonZeros(); ++p) {
    if (t.innerIndexPtr()[p] != a.innerIndexPtr()[p] || t.valuePtr()[p] != a.valuePtr()[p]) {
      return false;
    }
  }
  return true;
}

SymmetricProducts::SymmetricProducts(
    const std::vector<const Eigen::SparseMatrix<double>*>& matrices, SecondLane& lane)
    : lane_(&lane) {
  if (matrices.empty()) throw std::invalid_argument("SymmetricProducts: no matrix");
  n_ = matrices.front()->rows();
  for (const Eigen::SparseMatrix<double>* a : matrices) {
    if (a->rows() != n_ || a->cols() != n_ || !a->isCompressed()) {
      throw std::invalid_argument(
          "SymmetricProducts: the matrices must be square, compressed, "
          "of one size");
    }
    if (exactly_symmetric(*a)) {
      by_rows_.push_back({a->outerIndexPtr(), a->innerIndexPtr(), a->valuePtr()});
    } else {
      copies_.push_back(std::make_unique<Eigen::SparseMatrix<double, Eigen::RowMajor>>(*a));
      const auto& c = *copies_.back();
      by_rows_.push_back({c.outerIndexPtr(), c.innerIndexPtr(), c.valuePtr()});
    }
  }
  // Lane 0 takes the rows up to half the entries of all matrices.
  double total = 0.0;
  for (const ByRows& a : by_rows_) total += a.outer[n_];
  double before = 0.0;
  for (split_ = 0; split_ < n_ && 2.0 * before < total; ++split_) {
    for (const ByRows& a : by_rows_) before += a.outer[split_ + 1] - a.outer[split_];
  }
}

SymmetricProducts::~SymmetricProducts() = default;

int SymmetricProducts::copies() const { return static_cast<int>(copies_.size()); }

void SymmetricProducts::rows(std::span<const ProductInput> inputs, Eigen::Index first,
                             Eigen::Index end, double* y) const {
  const std::size_t terms = by_rows_.size();
  for (Eigen::Index i = first; i < end; ++i) {
    double sum = 0.0;
    for (std::size_t k = 0; k < terms; ++k) {
      const ByRows& a = by_rows_[k];
      const ProductInput& u = inputs[k];
      double part = 0.0;
      if (u.v1 == nullptr) {
        for (int p = a.outer[i]; p < a.outer[i + 1]; ++p) part += a.values[p] * u.v0[a.inner[p]];
        sum += u.c0 * part;
      } else {
        for (int p = a.outer[i]; p < a.outer[i + 1]; ++p) {
          const int j = a.inner[p];
          part += a.values[p] * (u.c0 * u.v0[j] + u.c1 * u.v1[j]);
        }
        sum += part;
      }
    }
    y[i] = sum;
  }
}

void SymmetricProducts::apply(std::span<const ProductInput> inputs, double* y) const {
  if (inputs.size() != by_rows_.size()) {
    throw std::invalid_argument("SymmetricProducts: one input per matrix");
  }
  lane_->run([&] { rows(inputs, 0, split_, y); }, [&] { rows(inputs, split_, n_, y); });
}

}  // namespace condyn
