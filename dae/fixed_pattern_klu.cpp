// KLU with its analysis kept across factorizations (dae/fixed_pattern_klu.hpp).

#include "dae/fixed_pattern_klu.hpp"

#include <Eigen/KLUSupport>

namespace condyn {

struct FixedPatternKlu::Impl {
  Eigen::KLU<Eigen::SparseMatrix<double>> klu;
};

FixedPatternKlu::FixedPatternKlu() : impl_(std::make_unique<Impl>()) {}
FixedPatternKlu::~FixedPatternKlu() = default;

bool FixedPatternKlu::factor(const Eigen::SparseMatrix<double>& matrix) {
  if (!analysed_) {
    impl_->klu.analyzePattern(matrix);
    if (impl_->klu.info() != Eigen::Success) return false;
    analysed_ = true;
  }
  impl_->klu.factorize(matrix);
  return impl_->klu.info() == Eigen::Success;
}

Eigen::VectorXd FixedPatternKlu::solve(const Eigen::VectorXd& rhs) const {
  return impl_->klu.solve(rhs);
}

}  // namespace condyn
