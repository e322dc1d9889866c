#pragma once
/// One factorization of a sparse symmetric matrix, for its definiteness and for solves with it:
/// CHOLMOD's supernodal Cholesky (dense kernels over OpenBLAS, loaded on first use) above
/// kCholmodAbove rows, Eigen's simplicial LDLᵀ at or below it and wherever CHOLMOD cannot be
/// loaded. Eigen's has no dense kernels: on a 3D mesh of 10⁵ DOFs its fill makes it take minutes
/// (docs/benchmarks.md); below 10⁴ it is fast and needs no library loaded. Used by the
/// definiteness check of matrix files and the modes' shift-invert Lanczos.

#include <Eigen/Sparse>
#include <memory>
#include <string>

#include "models/core/eigen_decompositions.hpp"

namespace condyn {

class FixedPatternCholmod;

/// Rows above which SymmetricFactor uses CHOLMOD.
inline constexpr Eigen::Index kCholmodAbove = 10000;

class SymmetricFactor {
 public:
  /// Factors `a`: square, symmetric, both triangles stored, compressed. Throws std::bad_alloc
  /// when CHOLMOD runs out of memory.
  explicit SymmetricFactor(const Eigen::SparseMatrix<double>& a);
  ~SymmetricFactor();
  SymmetricFactor(const SymmetricFactor&) = delete;
  SymmetricFactor& operator=(const SymmetricFactor&) = delete;

  /// Whether every pivot is positive (the matrix is positive definite to roundoff).
  [[nodiscard]] bool positive_definite() const { return definite_; }
  /// The smallest pivot over the largest (dᵢ of L D Lᵀ, or lᵢᵢ² of L Lᵀ): near roundoff for a
  /// singular matrix. Only when positive_definite() (throws std::logic_error otherwise).
  [[nodiscard]] double pivot_ratio() const;
  /// a⁻¹ b. Only when positive_definite() (throws std::logic_error otherwise).
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// "a sparse Cholesky factorization" or "a sparse LDLt", for messages.
  [[nodiscard]] std::string method() const;
  /// What the factorization found when the matrix is not positive definite: "meets a pivot that
  /// is not positive" (Cholesky stops at the first), "has N negative pivots" or "has a zero
  /// pivot" (LDLᵀ); empty when it is positive definite.
  [[nodiscard]] const std::string& finding() const { return finding_; }

 private:
  std::unique_ptr<FixedPatternCholmod> cholmod_;
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> ldlt_;
  bool definite_ = false;
  std::string finding_;
};

}  // namespace condyn
