#pragma once
/// A sparse Jacobian assembled from blocks, J = Σ scale_k · S_k placed at (row_k, col_k), with a
/// pattern fixed once: the formulations declare their blocks' patterns at construction and only
/// accumulate values in the Jacobian callback (no allocation, no pattern change, as KLU wants).

#include <Eigen/Sparse>
#include <vector>

namespace condyn {

/// A Jacobian's values in a fixed pattern, as a view: the integrator maps its own matrix's value
/// array over the pattern's index arrays, so no staging copy of the matrix is kept.
using JacobianMap = Eigen::Map<Eigen::SparseMatrix<double>>;

/// The view of a matrix that has the pattern (tests, the dense solver's staging matrix).
[[nodiscard]] inline JacobianMap map_of(Eigen::SparseMatrix<double>& J) {
  return {J.rows(), J.cols(), J.nonZeros(), J.outerIndexPtr(), J.innerIndexPtr(), J.valuePtr()};
}

/// A fixed sparsity pattern in compressed columns, indices only: the values live in the
/// integrator's own matrix (KLU's), so the pattern keeps no value array of its own (one would be
/// written with zeros and never read, issue 12).
struct JacobianPattern {
  int size = 0;            ///< rows = columns
  std::vector<int> outer;  ///< size + 1 column starts
  std::vector<int> inner;  ///< row indices, ascending within each column
  [[nodiscard]] Eigen::Index nonZeros() const { return static_cast<Eigen::Index>(inner.size()); }
  /// The view of nonZeros() values, `values`, in this pattern (its index arrays are never
  /// written through the view).
  [[nodiscard]] JacobianMap map(double* values) const {
    return {size,  size, nonZeros(), const_cast<int*>(outer.data()), const_cast<int*>(inner.data()),
            values};
  }
  /// The pattern as a matrix of stored zeros (the dense solver's staging matrix, tests).
  [[nodiscard]] Eigen::SparseMatrix<double> matrix() const;
};

class BlockJacobian {
 public:
  using Sparse = Eigen::SparseMatrix<double>;

  explicit BlockJacobian(int size = 0) : size_(size) {}

  /// Build phase: the entries of S, placed at (row0, col0), are part of the pattern.
  void declare(int row0, int col0, const Sparse& S);
  /// Build phase: the diagonal entries (row0 + k, col0 + k), k < count, are part of the pattern.
  void declare_identity(int row0, int col0, int count);
  /// Ends the build phase; the full diagonal is always included (structural nonsingularity).
  void finish();

  [[nodiscard]] const JacobianPattern& pattern() const { return pattern_; }

  /// Fill phase, on a matrix with pattern(): J(row0 + i, col0 + j) += scale · S(i, j). Throws
  /// std::logic_error when S has an entry outside the declared pattern.
  static void add(JacobianMap& J, int row0, int col0, const Sparse& S, double scale = 1.0);
  static void add_identity(JacobianMap& J, int row0, int col0, int count, double scale);

 private:
  /// A declared block's pattern at (row0, col0): its compressed column starts and row indices
  /// (4 bytes an entry where triplets take 16: on large models the triplets and their sort were
  /// most of `info`'s time and the build's largest transient, issue 12).
  struct Block {
    int row0 = 0, col0 = 0;
    std::vector<int> starts, rows;
  };
  int size_;
  std::vector<Block> blocks_;
  JacobianPattern pattern_;
};

}  // namespace condyn
