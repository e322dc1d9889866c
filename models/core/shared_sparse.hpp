#pragma once
/// A sparse matrix held once by every object that reads it: the Model's stiffness K is the one
/// its LinearSystem evaluates (at 10⁶ DOFs a copy of K is 200 MB; issue 12). Read it with * and
/// ->; write it, while the model is being built, through edit(), which copies the matrix first if
/// it is shared already, so that nobody else's copy changes.

#include <Eigen/Sparse>
#include <memory>

namespace condyn {

class SharedSparse {
 public:
  using Sparse = Eigen::SparseMatrix<double>;

  SharedSparse() : matrix_(std::make_shared<Sparse>()) {}

  [[nodiscard]] const Sparse& operator*() const { return *matrix_; }
  [[nodiscard]] const Sparse* operator->() const { return matrix_.get(); }
  /// The matrix, to change: this object's own (copied first when it is shared).
  [[nodiscard]] Sparse& edit() {
    if (matrix_.use_count() > 1) matrix_ = std::make_shared<Sparse>(*matrix_);
    return *matrix_;
  }
  /// The matrix for another reader to hold: the same one, not a copy.
  [[nodiscard]] std::shared_ptr<const Sparse> share() const { return matrix_; }

 private:
  std::shared_ptr<Sparse> matrix_;
};

}  // namespace condyn
