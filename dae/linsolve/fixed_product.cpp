// L X R with fixed patterns (dae/linsolve/fixed_product.hpp).

#include "dae/linsolve/fixed_product.hpp"

#include <algorithm>

namespace condyn {

FixedProduct::FixedProduct(const Sparse& left, const Sparse& right) : left_(left), right_(right) {
  left_.makeCompressed();
  right_.makeCompressed();
}

void FixedProduct::plan(const Sparse& x) {
  outer_.assign(x.outerIndexPtr(), x.outerIndexPtr() + x.outerSize() + 1);
  inner_.assign(x.innerIndexPtr(), x.innerIndexPtr() + x.nonZeros());
  struct Raw {
    Eigen::Index row, col, src;
    double weight;
  };
  std::vector<Raw> raw;
  for (Eigen::Index l = 0; l < x.outerSize(); ++l) {
    for (Eigen::Index p = x.outerIndexPtr()[l]; p < x.outerIndexPtr()[l + 1]; ++p) {
      const Eigen::Index k = x.innerIndexPtr()[p];  // X(k, l) at p
      for (Sparse::InnerIterator li(left_, k); li; ++li) {
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator ri(right_, l); ri; ++ri)
          raw.push_back({li.row(), ri.col(), p, li.value() * ri.value()});
      }
    }
  }
  std::vector<Eigen::Triplet<double>> pattern;
  pattern.reserve(raw.size());
  for (const Raw& r : raw) pattern.emplace_back(r.row, r.col, 1.0);
  result_.resize(left_.rows(), right_.cols());
  result_.setFromTriplets(pattern.begin(), pattern.end());
  result_.makeCompressed();
  terms_.clear();
  terms_.reserve(raw.size());
  for (const Raw& r : raw) {
    const Sparse::StorageIndex* inner = result_.innerIndexPtr();
    const Sparse::StorageIndex* begin = inner + result_.outerIndexPtr()[r.col];
    const Sparse::StorageIndex* end = inner + result_.outerIndexPtr()[r.col + 1];
    const Eigen::Index at = std::lower_bound(begin, end, r.row) - inner;
    terms_.push_back({at, r.src, r.weight});
  }
}

const FixedProduct::Sparse& FixedProduct::operator()(const Sparse& x) {
  const bool same = x.isCompressed() && static_cast<Eigen::Index>(inner_.size()) == x.nonZeros() &&
                    static_cast<Eigen::Index>(outer_.size()) == x.outerSize() + 1 &&
                    std::equal(outer_.begin(), outer_.end(), x.outerIndexPtr()) &&
                    std::equal(inner_.begin(), inner_.end(), x.innerIndexPtr());
  if (!same) {
    if (!x.isCompressed()) {
      Sparse compressed = x;
      compressed.makeCompressed();
      plan(compressed);
      return (*this)(compressed);
    }
    plan(x);
  }
  double* values = result_.valuePtr();
  std::fill(values, values + result_.nonZeros(), 0.0);
  const double* source = x.valuePtr();
  for (const Term& term : terms_) values[term.dest] += term.weight * source[term.src];
  return result_;
}

}  // namespace condyn
