#pragma once
/// The reactions of the paths that do not carry λ (elimination, the exact solution), from the
/// full equations of motion.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/model.hpp"

namespace condyn {

/// Multipliers recovered from the full equations at one time: ρ = M u'' + C u' + K u − f(t)
/// (the chapter's reaction recovery, eqs. 5.8 and 5.12, for every DOF at once) and
/// λ = −(A Aᵀ)⁻¹ A ρ, exact when ρ lies in range(Aᵀ), as it does for a solution of the
/// constrained equations. Used by the paths that do not carry λ (elimination, exact solution).
class MultiplierRecovery {
 public:
  explicit MultiplierRecovery(const Model& model);
  [[nodiscard]] Eigen::VectorXd operator()(double t, const Eigen::VectorXd& u,
                                           const Eigen::VectorXd& v,
                                           const Eigen::VectorXd& a) const;

 private:
  const Model& model_;
  Eigen::VectorXd scale_;                                   ///< D: a power of two per row
  Eigen::SparseMatrix<double> scaled_;                      ///< Â = D A
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> aat_;  ///< of Â Âᵀ
};

}  // namespace condyn
