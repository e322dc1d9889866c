#pragma once
/// Massless DOFs that no constraint touches (issue 13): only their stiffness or damping can hold
/// them. The model checks (models/assembly/mass_regularity.cpp), the schemes' refusals
/// (dae/run/solve.cpp) and the DAE formulations (dae/interface/held_massless.hpp) all ask these
/// questions.

#include <Eigen/Sparse>
#include <optional>
#include <string>
#include <vector>

namespace condyn {

/// The DOFs with a zero column of M and of A (A may have no rows), ascending. An explicitly
/// stored zero counts as zero.
[[nodiscard]] std::vector<int> unconstrained_massless_dofs(const Eigen::SparseMatrix<double>& M,
                                                           const Eigen::SparseMatrix<double>& A);

/// The unconstrained massless DOFs split by what holds their momentum row C_h· u' + K_h· u = f_h:
/// `undamped` (C's row and column h zero: an algebraic equation for u_h) and `damped` (c_hh ≠ 0:
/// first order in u_h). `unheld`: neither K_hh nor c_hh is nonzero (nothing holds them);
/// `coupled`: C_h· ≠ 0 but c_hh = 0 (neither algebraic nor first order). C may be 0 x 0.
struct HeldDofs {
  std::vector<int> undamped, damped, unheld, coupled;
  [[nodiscard]] bool empty() const { return undamped.empty() && damped.empty(); }
};
[[nodiscard]] HeldDofs held_massless_dofs(const Eigen::SparseMatrix<double>& M,
                                          const Eigen::SparseMatrix<double>& C,
                                          const Eigen::SparseMatrix<double>& K,
                                          const Eigen::SparseMatrix<double>& A);

/// S's block of rows and columns `dofs` (ascending), compressed.
[[nodiscard]] Eigen::SparseMatrix<double> principal_block(const Eigen::SparseMatrix<double>& S,
                                                          const std::vector<int>& dofs);

/// When K_HuHu (undamped) or C_HdHd (damped) is singular, what is: a mechanism of massless DOFs
/// that their stiffness (damping) does not hold. Otherwise nothing.
[[nodiscard]] std::optional<std::string> singular_held_block(const HeldDofs& held,
                                                             const Eigen::SparseMatrix<double>& C,
                                                             const Eigen::SparseMatrix<double>& K);

}  // namespace condyn
