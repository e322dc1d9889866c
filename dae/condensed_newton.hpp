#pragma once
/// IDA's Newton systems of the index1 and GGL formulations of a linear model (constant M, C, K,
/// A), condensed from [u; v; λ (; μ)] to [u; λ (; μ)] (issue 12, item 6). With
/// J = ∂F/∂y + cj ∂F/∂y' of dae/multiplier_dae.hpp, K = −∂f/∂u, C = −∂f/∂v, S = K + cj C + cj² M,
/// and J x = r, x = [du; dv; dλ (; dμ)], r = [r1; r2; r3 (; r4)]:
///
///   index1: dv = cj du − r1,
///     [S  Aᵀ] [du]   [r2 + (C + cj M) r1   ]
///     [A  0 ] [dλ] = [(r3 + cj A r1) / cj² ]
///   GGL (A_p the position rows): dv = cj du + A_pᵀ dμ − r1,
///     [S     Aᵀ  (C + cj M) A_pᵀ] [du]   [r2 + (C + cj M) r1]
///     [cj A  0   A A_pᵀ         ] [dλ] = [r3 + A r1         ]
///     [A_p   0   0              ] [dμ]   [r4                ]
///
/// n + m (+ p) unknowns for KLU instead of 2n + m (+ p), and IDA never forms its Jacobian. The
/// pattern is the union of the blocks' patterns, fixed, analysed once.

#include <Eigen/Sparse>

#include "dae/fixed_pattern_klu.hpp"
#include "dae/newton_system.hpp"
#include "models/scheme.hpp"

namespace condyn {

class CondensedNewton final : public NewtonSystem {
 public:
  /// scheme index1 or ggl (else std::invalid_argument); select_p (p x m) picks GGL's position
  /// rows. C may be empty (no damping).
  CondensedNewton(Scheme scheme, const Eigen::SparseMatrix<double>& M,
                  const Eigen::SparseMatrix<double>& C, const Eigen::SparseMatrix<double>& K,
                  const Eigen::SparseMatrix<double>& A,
                  const Eigen::SparseMatrix<double>& select_p);

  bool setup(double cj) override;
  void solve(Eigen::Ref<Eigen::VectorXd> b) override;
  [[nodiscard]] long nonzeros() const override { return pattern_.nonZeros(); }

 private:
  /// The condensed matrix for cj, its entries placed on pattern_ (a superset of its own).
  [[nodiscard]] Eigen::SparseMatrix<double> matrix(double cj, bool magnitudes) const;

  Scheme scheme_;
  Eigen::SparseMatrix<double> M_, C_, K_, A_, Ap_, ApT_, AApT_;
  int n_, m_, p_;
  double cj_ = 0.0;
  Eigen::SparseMatrix<double> pattern_;
  FixedPatternKlu klu_;
};

}  // namespace condyn
