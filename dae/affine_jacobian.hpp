#pragma once
/// A Jacobian of the form J = J0 + cj J1 with constant J0, J1: the case for every linear
/// formulation, where F(t, y, y') = J0 y + J1 y' − b(t). Values are stored aligned with the union
/// pattern so the callback is one fused loop, no allocation.

#include <Eigen/Sparse>
#include <vector>

namespace condyn {

class AffineJacobian {
 public:
  AffineJacobian() = default;
  /// J0 = dF/dy, J1 = dF/dy' (same size, any patterns). The diagonal is always in the pattern so
  /// the linear solver sees a structurally nonsingular matrix.
  AffineJacobian(const Eigen::SparseMatrix<double>& J0, const Eigen::SparseMatrix<double>& J1);

  [[nodiscard]] const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }
  /// Writes J0 + cj J1 into J, which must have pattern().
  void fill(double cj, Eigen::SparseMatrix<double>& J) const;

 private:
  Eigen::SparseMatrix<double> pattern_;
  std::vector<double> v0_, v1_;
};

}  // namespace condyn
