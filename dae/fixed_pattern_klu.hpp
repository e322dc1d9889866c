#pragma once
/// KLU (SuiteSparse, through Eigen's KLUSupport) on a sequence of matrices that share one pattern,
/// as condyn's own Newton solvers factor them (dae/kkt_newton.hpp, dae/condensed_newton.hpp):
/// the symbolic analysis at the first factorization, numeric refactorizations after. KLU stays out
/// of the header.

#include <Eigen/Sparse>
#include <memory>

namespace condyn {

class FixedPatternKlu {
 public:
  FixedPatternKlu();
  ~FixedPatternKlu();
  FixedPatternKlu(const FixedPatternKlu&) = delete;
  FixedPatternKlu& operator=(const FixedPatternKlu&) = delete;

  /// Factors `matrix`, whose pattern must be that of the first matrix factored; false when it is
  /// singular (or the analysis failed).
  bool factor(const Eigen::SparseMatrix<double>& matrix);
  /// x with (last matrix factored) x = rhs.
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool analysed_ = false;
};

}  // namespace condyn
