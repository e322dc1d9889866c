#pragma once
/// Which sparse factorization a run's Newton matrices get ([solve] linear_solver): CHOLMOD's
/// Cholesky where the matrix is symmetric positive definite by construction (elimination's
/// condensed K̂ + cj Ĉ + cj² M̂: dae/linsolve/condensed_newton.hpp), KLU's LU everywhere else (the
/// saddle points of the multiplier schemes, the integrators' unsymmetric Jacobians over [u; v]).
///
/// The choice of `auto` is made from the pattern: one symbolic analysis per candidate, KLU's
/// (AMD on the pattern, predicted_klu_factor) and CHOLMOD's under each ordering its build
/// offers (models/core/fixed_pattern_cholmod.hpp); CHOLMOD when its least-fill ordering's factor
/// takes less memory than KLU's L and U. The analyses cost no factorization.

#include <optional>
#include <string>
#include <vector>

#include "dae/linsolve/newton_system.hpp"
#include "models/core/fixed_pattern_cholmod.hpp"
#include "models/core/scheme.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

/// The symbolic analyses of one symmetric positive-definite Newton matrix.
struct FactorizationCandidates {
  int unknowns = 0;
  long nonzeros = 0;
  double klu_entries = 0.0;               ///< KLU's L and U, predicted (AMD)
  double klu_bytes = 0.0;                 ///< their values and row indices
  std::vector<CholmodCandidate> cholmod;  ///< one per ordering the build offers
  /// Whether CHOLMOD's least-fill factor takes less memory than KLU's (auto's rule).
  [[nodiscard]] bool cholmod_smaller() const;
  /// One line per candidate: entries, flops (CHOLMOD) and memory.
  [[nodiscard]] std::string describe() const;
};

/// Analyses `matrix` (square, compressed, symmetric, both triangles) under every candidate.
[[nodiscard]] FactorizationCandidates analyse_factorizations(
    const Eigen::SparseMatrix<double>& matrix);

struct FactorizationChoice {
  bool cholmod = false;  ///< CHOLMOD factors the (condensed) Newton matrix; else KLU or dense
  std::string reason;    ///< why, for the summary and `info`
  /// auto would have analysed the matrix for CHOLMOD, which could not be loaded: KLU, and the
  /// run says why.
  bool cholmod_unavailable = false;
  /// CHOLMOD's least-fill ordering, under which the run analyses the matrix again (once), and
  /// its factor's predicted entries and bytes (the run's memory estimate counts them).
  std::string ordering{};
  double factor_entries = 0.0;
  double factor_bytes = 0.0;
  /// CHOLMOD's count of the flops of one factorization under that ordering.
  double factor_flops = 0.0;
};

/// The rate at which factorization_time_warning predicts a factorization's time: above the
/// rates measured with one OpenBLAS thread on the benchmark machine (docs/benchmarks.md: about
/// 3e9 flop/s on the 2D braced wall's small supernodes, 2.5e10 on the 3D lattice's of 10⁵ DOFs),
/// so that the time it predicts is a lower bound.
inline constexpr double kFactorFlopRate = 5e10;
/// The predicted time of one factorization above which info warns.
inline constexpr double kSlowFactorSeconds = 10.0;

/// Said by `info` when the chosen factorization of the Newton matrix is predicted to take more
/// than kSlowFactorSeconds at kFactorFlopRate (a run refactors every few steps at its start and
/// wherever the step changes much), with the figures; nothing otherwise.
[[nodiscard]] std::optional<std::string> factorization_time_warning(
    const FactorizationChoice& choice);

/// The factorization of a run under `scheme` (resolved) whose condensed Newton system, when it
/// has one, is `newton` (nullptr: none). Throws SchemeNotApplicable (where: the
/// `solve.linear_solver` key) when CHOLMOD is named and the Newton matrix is not symmetric
/// positive definite by construction, or CHOLMOD or OpenBLAS cannot be loaded (auto then keeps
/// KLU).
[[nodiscard]] FactorizationChoice choose_factorization(const NewtonSystem* newton, Scheme scheme,
                                                       const SolveSpec& settings);

}  // namespace condyn
