// A sparse symmetric matrix factored by CHOLMOD or Eigen by its size
// (models/core/symmetric_factor.hpp).

#include "models/core/symmetric_factor.hpp"

#include <stdexcept>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/fixed_pattern_cholmod.hpp"
#include "models/core/load_library.hpp"

namespace condyn {

SymmetricFactor::SymmetricFactor(const Eigen::SparseMatrix<double>& a) {
  if (a.rows() > kCholmodAbove) {
    try {
      cholmod_ = std::make_unique<FixedPatternCholmod>();
      definite_ = cholmod_->factor(a);
      if (!definite_) finding_ = "meets a pivot that is not positive";
      return;
    } catch (const LibraryUnavailable&) {
      cholmod_.reset();  // Eigen's factorization below gives the same answer, slower on meshes
    }
  }
  ldlt_ = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(a);
  if (ldlt_->info() != Eigen::Success) {
    finding_ = "has a zero pivot";
    return;
  }
  const Eigen::VectorXd d = ldlt_->vectorD();
  // Eigen reports an exact zero pivot as a failure: the others are positive or negative.
  const auto negative = (d.array() < 0.0).count();
  definite_ = negative == 0;
  if (!definite_)
    finding_ = "has " + std::to_string(negative) + " negative pivot" + (negative == 1 ? "" : "s");
}

SymmetricFactor::~SymmetricFactor() = default;

double SymmetricFactor::pivot_ratio() const {
  if (!definite_) throw std::logic_error("SymmetricFactor: pivot ratio of an indefinite matrix");
  if (cholmod_) return cholmod_->pivot_ratio();
  const Eigen::VectorXd d = ldlt_->vectorD();
  return d.minCoeff() / d.maxCoeff();
}

Eigen::VectorXd SymmetricFactor::solve(const Eigen::VectorXd& b) const {
  if (!definite_) throw std::logic_error("SymmetricFactor: solve with an indefinite matrix");
  if (!cholmod_) return ldlt_->solve(b);
  Eigen::VectorXd x = b;
  cholmod_->solve_in_place(x);
  return x;
}

std::string SymmetricFactor::method() const {
  return cholmod_ ? "a sparse Cholesky factorization" : "a sparse LDLt";
}

}  // namespace condyn
