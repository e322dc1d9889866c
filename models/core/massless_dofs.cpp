// Massless DOFs that no constraint touches, and what holds them (models/core/massless_dofs.hpp).

#include "models/core/massless_dofs.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <cstddef>

#include "models/core/eigen_decompositions.hpp"

namespace condyn {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

bool zero_column(const Sparse& S, int j) {
  if (S.cols() == 0) return true;
  for (Sparse::InnerIterator it(S, j); it; ++it) {
    if (it.value() != 0.0) return false;
  }
  return true;
}

/// Singular to roundoff: for a symmetric block (K and C of structures), a pivot of its sparse
/// LDLᵀ at most 1e-12 of the largest; otherwise a failed sparse LU (exact zero pivot).
bool singular(const Sparse& S) {
  if (S.rows() == 0) return false;
  const Sparse St = S.transpose();
  if ((S - St).norm() <= 1e-14 * S.norm()) {
    const Eigen::SimplicialLDLT<Sparse> ldlt(S);
    if (ldlt.info() != Eigen::Success) return true;
    const Eigen::VectorXd d = ldlt.vectorD().cwiseAbs();
    return d.minCoeff() <= 1e-12 * d.maxCoeff();
  }
  Eigen::SparseLU<Sparse> lu;
  lu.compute(S);
  return lu.info() != Eigen::Success;
}

}  // namespace

std::vector<int> unconstrained_massless_dofs(const Sparse& M, const Sparse& A) {
  std::vector<int> dofs;
  for (int j = 0; j < static_cast<int>(M.cols()); ++j) {
    if (zero_column(M, j) && zero_column(A, j)) dofs.push_back(j);
  }
  return dofs;
}

HeldDofs held_massless_dofs(const Sparse& M, const Sparse& C, const Sparse& K, const Sparse& A) {
  HeldDofs held;
  const bool damping = C.rows() == M.rows() && C.nonZeros() > 0;
  for (int j : unconstrained_massless_dofs(M, A)) {
    const double c = damping ? C.coeff(j, j) : 0.0;
    if (c != 0.0) {
      held.damped.push_back(j);
    } else if (damping && !zero_column(C, j)) {
      held.coupled.push_back(j);
    } else if (K.rows() > j && K.coeff(j, j) != 0.0) {
      held.undamped.push_back(j);
    } else {
      held.unheld.push_back(j);
    }
  }
  return held;
}

Sparse principal_block(const Sparse& S, const std::vector<int>& dofs) {
  std::vector<int> local(static_cast<std::size_t>(S.rows()), -1);
  for (std::size_t k = 0; k < dofs.size(); ++k)
    local[static_cast<std::size_t>(dofs[k])] = static_cast<int>(k);
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    for (Sparse::InnerIterator it(S, dofs[k]); it; ++it) {
      const int r = local[static_cast<std::size_t>(it.row())];
      if (r >= 0) trip.emplace_back(r, static_cast<int>(k), it.value());
    }
  }
  const auto size = static_cast<Eigen::Index>(dofs.size());
  Sparse block(size, size);
  block.setFromTriplets(trip.begin(), trip.end());
  block.makeCompressed();
  return block;
}

std::optional<std::string> singular_held_block(const HeldDofs& held, const Sparse& C,
                                               const Sparse& K) {
  if (singular(principal_block(K, held.undamped)))
    return "their stiffness block K_hh is singular: a mechanism of massless DOFs";
  if (!held.damped.empty() && singular(principal_block(C, held.damped)))
    return "their damping block C_hh is singular: a mechanism of massless DOFs";
  return std::nullopt;
}

}  // namespace condyn
