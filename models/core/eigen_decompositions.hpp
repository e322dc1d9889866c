#pragma once
/// Eigen's dense and sparse decompositions of double matrices, compiled once in
/// eigen_decompositions.cpp instead of in every translation unit that uses them.
///
/// A class template's members are compiled wherever they are used, and these are among the most
/// expensive in the build: under the sanitized build's flags one translation unit that uses
/// SelfAdjointEigenSolver or SparseLU spends half a minute on it
/// (docs/benchmarks.md, "The test command"). An explicit instantiation declaration (`extern
/// template`) tells each user the members exist elsewhere; the .cpp defines them. Results are
/// unchanged: the same code, compiled with the same flags, in one place.
///
/// Every file that names one of these decompositions includes this header
/// (scripts/check_eigen_instances.cmake checks it at every build). The members declared here are
/// the ones computed from a MatrixXd or a SparseMatrix<double> (an lvalue of that type, not an
/// expression: a decomposition computed from an expression compiles its own copy, correct but
/// slow). Singular values come from LAPACK (models/core/singular_values.hpp), not from Eigen's
/// SVDs.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>

namespace condyn::eigen_instances {
using LdltBase = Eigen::SimplicialCholeskyBase<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>;
}  // namespace condyn::eigen_instances

// Classes whose work is done by members that are not templates (compute, computeInPlace,
// factorize, analyzePattern): the class's declaration covers them.
extern template class Eigen::ColPivHouseholderQR<Eigen::MatrixXd>;
extern template class Eigen::HouseholderQR<Eigen::MatrixXd>;
extern template class Eigen::FullPivLU<Eigen::MatrixXd>;
extern template class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>;
extern template class Eigen::SparseLU<Eigen::SparseMatrix<double>>;
// Classes whose work is done by a member template: that member, computed from the plain type.
extern template class Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;
extern template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>&
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>::compute(const Eigen::EigenBase<Eigen::MatrixXd>&,
                                                        int);
extern template class Eigen::LLT<Eigen::MatrixXd>;
extern template Eigen::LLT<Eigen::MatrixXd>& Eigen::LLT<Eigen::MatrixXd>::compute(
    const Eigen::EigenBase<Eigen::MatrixXd>&);
extern template class Eigen::LDLT<Eigen::MatrixXd>;
extern template Eigen::LDLT<Eigen::MatrixXd>& Eigen::LDLT<Eigen::MatrixXd>::compute(
    const Eigen::EigenBase<Eigen::MatrixXd>&);
extern template class Eigen::SimplicialCholeskyBase<
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>;
extern template void condyn::eigen_instances::LdltBase::factorize_preordered<true>(
    const condyn::eigen_instances::LdltBase::CholMatrixType&);
