// Coordinate partitioning's choice and its conditioning
// (dae/formulations/coordinate_partition.hpp).

#include "dae/formulations/coordinate_partition.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseQR>
#include <algorithm>
#include <cmath>

#include "dae/formulations/master_slave.hpp"
#include "models/core/row_scales.hpp"

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

double pivot_ratio(const Eigen::SparseMatrix<double>& A, const CoordinatePartition& partition) {
  if (partition.dependent.empty()) return 1.0;
  Eigen::SparseMatrix<double> block = row_scales(A).asDiagonal() * (A * partition.select_dependent);
  block.makeCompressed();
  Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr;
  // No rank decision: every column is factored, so a singular block shows as a zero |R_ii|.
  qr.setPivotThreshold(0.0);
  qr.compute(block);
  if (qr.info() != Eigen::Success) return 0.0;
  const Eigen::VectorXd d = Eigen::SparseMatrix<double>(qr.matrixR()).diagonal().cwiseAbs();
  const double largest = d.maxCoeff();
  return largest > 0.0 && std::isfinite(largest) ? d.minCoeff() / largest : 0.0;
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
