#pragma once
/// Static condensation of massless directions for the exact modal reference (issue 13): when the
/// mass matrix of M q'' + C q' + K q = Σ b_j τ_j(t) is singular on directions Z (an orthonormal
/// basis of null(M)) that stiffness holds (ZᵀKZ positive definite) and no damping acts on
/// (C Z = 0), those rows are static, ZᵀK q = Zᵀ f(t), and with R an orthonormal basis of range(M)
///
///   q = T x + Z (ZᵀKZ)⁻¹ Zᵀ f(t),   T = R − Z (ZᵀKZ)⁻¹ ZᵀK R        (Guyan's transformation)
///
/// turns the system into TᵀMT x'' + TᵀCT x' + TᵀKT x = Σ Tᵀb_j τ_j(t) with TᵀMT = RᵀMR positive
/// definite: the regular system ModalSolution solves. q' and q'' add the loads' exact
/// derivatives (a table's second derivative is 0 between samples; a step's jump moves q at once).
/// Damping on massless directions makes them first order, not static: refused.

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "validation/references/modal_exact.hpp"

namespace condyn {

struct StaticCondensation {
  LtiSystem reduced;                ///< in x; initial values Rᵀq0, Rᵀv0
  Eigen::MatrixXd T;                ///< n x r
  std::vector<Eigen::VectorXd> zh;  ///< Z (ZᵀKZ)⁻¹ Zᵀ b_j, one per forcing term
  std::vector<TimeTerm> terms;      ///< τ_j

  /// q, q', q'' from the reduced state at t.
  [[nodiscard]] LtiState expand(const LtiState& x, double t) const;
};

/// The condensation when M has a null space (eigenvalues at most 1e-12 of the largest), else
/// nothing. Throws ExactSolutionUnavailable when M is zero, when damping acts on the massless
/// directions, or when stiffness does not hold them.
[[nodiscard]] std::optional<StaticCondensation> condense_massless(const LtiSystem& system);

}  // namespace condyn
