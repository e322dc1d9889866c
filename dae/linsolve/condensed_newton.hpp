#pragma once
/// IDA's Newton systems of the index1 and GGL formulations of a linear model (constant M, C, K,
/// A), condensed from [u; v; λ (; μ)] to [u; λ (; μ)] (issue 12, item 6). With
/// J = ∂F/∂y + cj ∂F/∂y' of dae/formulations/multiplier_dae.hpp, K = −∂f/∂u, C = −∂f/∂v, S = K + cj
/// C + cj² M, and J x = r, x = [du; dv; dλ (; dμ)], r = [r1; r2; r3 (; r4)]:
///
///   index1: dv = cj du − r1,
///     [S  Aᵀ] [du]   [r2 + (C + cj M) r1   ]
///     [A  0 ] [dλ] = [(r3 + cj A r1) / cj² ]
///   GGL (A_p the position rows): dv = cj du + A_pᵀ dμ − r1,
///     [S     Aᵀ  (C + cj M) A_pᵀ] [du]   [r2 + (C + cj M) r1]
///     [cj A  0   A A_pᵀ         ] [dλ] = [r3 + A r1         ]
///     [A_p   0   0              ] [dμ]   [r4                ]
///
/// KLU factors these with dλ (and dμ) scaled so that the multipliers' pivots are of the order
/// of S's (scales()): unscaled, they lay some cj² max M_ii below them, and KLU's rcond test
/// rejected most refactorizations (each then pivoted afresh).
///
/// n + m (+ p) unknowns for KLU instead of 2n + m (+ p), and IDA never forms its Jacobian. The
/// pattern is the union of the blocks' patterns, fixed, analysed once; each setup fills its values
/// in place (dae/linsolve/block_jacobian.hpp) and refactors with the pivots kept
/// (dae/linsolve/fixed_pattern_klu.hpp), and solves use buffers allocated once: a matrix rebuilt
/// from triplets at each setup and vectors allocated at each solve cost large runs most of their
/// time in page faults (issue 12).

#include <Eigen/Sparse>

#include <array>
#include <memory>

#include "dae/linsolve/block_jacobian.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "dae/linsolve/kkt.hpp"
#include "dae/linsolve/newton_system.hpp"
#include "models/core/fixed_pattern_cholmod.hpp"
#include "models/core/scheme.hpp"
#include "models/core/symmetric_products.hpp"

namespace condyn {

class CondensedNewton final : public NewtonSystem {
 public:
  /// scheme index1 or ggl (else std::invalid_argument); select_p (p x m) picks GGL's position
  /// rows. C may be empty (no damping). The matrices are taken over (left empty).
  CondensedNewton(Scheme scheme, LinearMatrices&& matrices,
                  const Eigen::SparseMatrix<double>& select_p);
  ~CondensedNewton() override = default;
  /// Not copied or moved: products_ reads M_ and C_ where they are.
  CondensedNewton(const CondensedNewton&) = delete;
  CondensedNewton& operator=(const CondensedNewton&) = delete;
  CondensedNewton(CondensedNewton&&) = delete;
  CondensedNewton& operator=(CondensedNewton&&) = delete;

  bool setup(double cj) override;
  void solve(Eigen::Ref<Eigen::VectorXd> b) override;
  [[nodiscard]] long nonzeros() const override { return matrix_.nonZeros(); }
  /// Without constraints (elimination's reduced system), K + cj C + cj² M: symmetric, and
  /// positive definite for a stable model (M positive definite, K and C positive semi-definite).
  [[nodiscard]] const Eigen::SparseMatrix<double>* symmetric_matrix() const override {
    return m_ == 0 && p_ == 0 ? &matrix_ : nullptr;
  }
  bool use_cholmod(const std::string& ordering) override;
  /// KLU's factorizations that chose their pivots: the first, and those whose refactorization
  /// with the kept pivots looked ill-conditioned (dae/linsolve/fixed_pattern_klu.hpp).
  [[nodiscard]] long pivoting_factorizations() const { return klu_.pivoting_factorizations(); }

 private:
  using Sparse = Eigen::SparseMatrix<double>;

  struct Scales;
  /// dλ = s dλ̃, s = max |S_ii| / max |A_ij|; GGL's dμ = s / e dμ̃, e = max(max |(C + cj M)_ii|,
  /// max |S_ii| / cj) (the μ column holds (C + cj M) A_pᵀ beside S and A A_pᵀ in the λ rows);
  /// each the power of two nearest below, so that scaling rounds nothing. The constraint rows
  /// are left as they are: KLU scales every row by its largest entry. All 1 without
  /// constraints.
  [[nodiscard]] Scales scales(double cj) const;

  Scheme scheme_;
  Sparse M_, C_, K_, A_, At_, Ap_, ApT_, CApT_, MApT_, AApT_;
  int n_, m_, p_;
  double cj_ = 0.0;
  Sparse matrix_;  ///< the condensed matrix on its fixed pattern, values for cj_
  std::array<Eigen::VectorXd, 3> diagonals_;  ///< of K, C and M
  double largest_a_ = 0.0;                    ///< max |A_ij|
  struct Scales {
    double lambda = 1.0, mu = 1.0;  ///< dλ = lambda dλ̃, dμ = mu dμ̃
  };
  Scales scale_;  ///< scales(cj_)
  Eigen::VectorXd rhs_, r1_, work_;
  /// With constraints COLAMD: a column ordering leaves KLU free to pivot off the multipliers'
  /// zero diagonal block, where AMD's ordering of A + Aᵀ counts on diagonal pivots (a 2D mesh of
  /// 10⁴ DOFs under index1: 3.3e8 flops a factorization against 8.3e8; docs/benchmarks.md).
  /// Without (elimination's and penalty's symmetric S), AMD: COLAMD orders for SᵀS and doubles
  /// a mesh's factor.
  FixedPatternKlu klu_;
  std::unique_ptr<FixedPatternCholmod> cholmod_;  ///< set by use_cholmod(): factors instead of KLU
  /// (C + cj M) r₁ in one pass on two lanes on large models (models/core/symmetric_products.hpp);
  /// null on small ones.
  std::unique_ptr<SymmetricProducts> products_;
};

}  // namespace condyn
