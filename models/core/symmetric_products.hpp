#pragma once
/// y = Σₖ Aₖ uₖ over a fixed list of square sparse matrices, each uₖ a combination c₀ v₀ + c₁ v₁
/// formed entry by entry (no temporary vector), every row of y from one pass over the row's
/// entries of all matrices, the rows split between two lanes (models/core/second_lane.hpp) at
/// the row that halves the entries. The residuals of large linear models are a few such products
/// (M̂ ẇ + K̂ û + Ĉ w), each bound by memory bandwidth: one pass instead of one per matrix and the
/// second core's bandwidth beside the first's. Each row's sum runs in one fixed order whatever the
/// lanes, so one lane or two give the same y bit for bit.
///
/// A matrix stored by columns (Eigen's default) is read as its own transpose where it is exactly
/// symmetric (the entries of row i are those of column i); one that is not is copied once by rows.

#include <Eigen/Sparse>
#include <memory>
#include <span>
#include <vector>

namespace condyn {

class SecondLane;
/// SecondLane::shared() (models/core/second_lane.hpp).
SecondLane& default_lane();

/// Below this many entries in the matrices together Eigen's products serve (a fraction of a
/// millisecond: no second lane pays there).
inline constexpr double kLanedProductFewestEntries = 2e5;

/// uₖ = c0 v0 + c1 v1 (v1 may be null: uₖ = c0 v0). The vectors have the matrices' size.
struct ProductInput {
  const double* v0 = nullptr;
  double c0 = 1.0;
  const double* v1 = nullptr;
  double c1 = 0.0;
};

class SymmetricProducts {
 public:
  /// Keeps pointers to `matrices` (square, compressed, of one size): they must outlive this and
  /// not change. Throws std::invalid_argument when they are not. The products run on `lane`.
  explicit SymmetricProducts(const std::vector<const Eigen::SparseMatrix<double>*>& matrices,
                             SecondLane& lane = default_lane());
  ~SymmetricProducts();
  SymmetricProducts(const SymmetricProducts&) = delete;
  SymmetricProducts& operator=(const SymmetricProducts&) = delete;

  /// y = Σₖ Aₖ uₖ with uₖ from inputs[k] (one input per matrix, in order); y of the size.
  void apply(std::span<const ProductInput> inputs, double* y) const;
  /// Rows of lane 0 (the rest are lane 1's).
  [[nodiscard]] Eigen::Index split_row() const { return split_; }
  /// How many matrices are read through a copy by rows (not exactly symmetric).
  [[nodiscard]] int copies() const;

 private:
  void rows(std::span<const ProductInput> inputs, Eigen::Index first, Eigen::Index end,
            double* y) const;
  struct ByRows {
    const int* outer;
    const int* inner;
    const double* values;
  };
  std::vector<ByRows> by_rows_;
  std::vector<std::unique_ptr<Eigen::SparseMatrix<double, Eigen::RowMajor>>> copies_;
  Eigen::Index n_ = 0, split_ = 0;
  SecondLane* lane_;
};

/// Whether `a` (compressed) equals its transpose entry for entry, bitwise.
[[nodiscard]] bool exactly_symmetric(const Eigen::SparseMatrix<double>& a);

}  // namespace condyn
