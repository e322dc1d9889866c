// Coordinate partitioning's choice and its conditioning
// (dae/formulations/coordinate_partition.hpp).

#include "dae/formulations/coordinate_partition.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/master_slave.hpp"

namespace condyn {

CoordinatePartition choose_partition(const Eigen::SparseMatrix<double>& A) {
  const int n = static_cast<int>(A.cols());
  CoordinatePartition p;
  p.dependent = pivoted_slaves(A);
  p.independent_at.assign(static_cast<std::size_t>(n), -1);
  std::vector<bool> dependent(static_cast<std::size_t>(n), false);
  for (int d : p.dependent) dependent[static_cast<std::size_t>(d)] = true;
  for (int j = 0; j < n; ++j) {
    if (dependent[static_cast<std::size_t>(j)]) continue;
    p.independent_at[static_cast<std::size_t>(j)] = static_cast<int>(p.independent.size());
    p.independent.push_back(j);
  }
  std::vector<Eigen::Triplet<double>> select;
  for (std::size_t k = 0; k < p.dependent.size(); ++k)
    select.emplace_back(p.dependent[k], static_cast<int>(k), 1.0);
  p.select_dependent.resize(n, static_cast<Eigen::Index>(p.dependent.size()));
  p.select_dependent.setFromTriplets(select.begin(), select.end());
  return p;
}

namespace {

/// Hager's estimator stops at a local maximum of ‖X x‖₁ over ‖x‖₁ = 1, in two or three
/// iterations in practice; LAPACK's xLACN2 caps it at five.
constexpr int kHagerIterations = 5;

/// ‖X‖₁, X = A_d⁻¹ A_i, by Hager's method (Higham 1988, Algorithm 2.1): X x and Xᵀ ξ through
/// the LU of A_d (non-const: Eigen 3.4's transpose() view), A_i x as A times x scattered onto
/// the independent columns.
double dependent_sensitivity(const Eigen::SparseMatrix<double>& A, const CoordinatePartition& p,
                             Eigen::SparseLU<Eigen::SparseMatrix<double>>& lu) {
  const auto ni = static_cast<Eigen::Index>(p.independent.size());
  Eigen::VectorXd x = Eigen::VectorXd::Constant(ni, 1.0 / static_cast<double>(ni));
  Eigen::VectorXd scattered = Eigen::VectorXd::Zero(A.cols());
  Eigen::VectorXd z(ni);
  double estimate = 0.0;
  for (int it = 0; it < kHagerIterations; ++it) {
    for (Eigen::Index k = 0; k < ni; ++k)
      scattered[p.independent[static_cast<std::size_t>(k)]] = x[k];
    const Eigen::VectorXd y = lu.solve(A * scattered);
    estimate = std::max(estimate, y.lpNorm<1>());
    const Eigen::VectorXd sign = y.unaryExpr([](double v) { return v >= 0.0 ? 1.0 : -1.0; });
    const Eigen::VectorXd back = A.transpose() * Eigen::VectorXd(lu.transpose().solve(sign));
    for (Eigen::Index k = 0; k < ni; ++k) z[k] = back[p.independent[static_cast<std::size_t>(k)]];
    Eigen::Index j = 0;
    if (z.cwiseAbs().maxCoeff(&j) <= z.dot(x)) break;  // x is a local maximum
    x.setZero();
    x[j] = 1.0;
  }
  return estimate;
}

}  // namespace

double partition_quality(const Eigen::SparseMatrix<double>& A,
                         const CoordinatePartition& partition) {
  if (partition.dependent.empty() || partition.independent.empty()) return 1.0;
  Eigen::SparseMatrix<double> block = A * partition.select_dependent;
  block.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(block);
  if (lu.info() != Eigen::Success) return 0.0;
  const double sensitivity = dependent_sensitivity(A, partition, lu);
  return std::isfinite(sensitivity) ? 1.0 / (1.0 + sensitivity) : 0.0;
}

std::string dof_list(const std::vector<std::string>& names, const std::vector<int>& dofs,
                     std::size_t limit) {
  std::string out;
  for (std::size_t k = 0; k < dofs.size() && k < limit; ++k) {
    out += (k == 0 ? "" : ", ") + names[static_cast<std::size_t>(dofs[k])];
  }
  if (dofs.size() > limit) out += " and " + std::to_string(dofs.size() - limit) + " more";
  return out;
}

}  // namespace condyn
