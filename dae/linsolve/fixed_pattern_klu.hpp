#pragma once
/// KLU (SuiteSparse) on a sequence of matrices that share one pattern, as condyn's own Newton
/// solvers factor them (dae/formulations/kkt_newton.hpp, dae/linsolve/condensed_newton.hpp): the
/// symbolic analysis and a pivoting factorization at the first call, numeric refactorizations with
/// the same pivots after (klu_refactor: no allocation, no pivot search), and a fresh pivoting
/// factorization whenever the refactored matrix looks ill-conditioned (KLU's rcond estimate below
/// ε^(2/3), the test SUNDIALS' own KLU solver applies). KLU stays out of the header.
///
/// Called through KLU's C interface rather than Eigen's KLUSupport, which frees and reallocates
/// the numeric factors at every factorization: on large systems the page faults of those fresh
/// allocations outweighed the factorization (issue 12; docs/benchmarks.md).

#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "models/core/memory_estimate.hpp"

namespace condyn {

/// KLU's fill-reducing ordering (0 AMD, KLU's default; 1 COLAMD), and whether a refactored
/// matrix whose rcond estimate is small is kept when KLU's condest (dearer, more accurate) finds
/// its condition number at most 1/ε^(2/3).
///
/// From `band_ordering_from` unknowns on, the first factorization also tries a bandwidth-reducing
/// ordering (dae/linsolve/band_ordering.hpp) and keeps it when its factor has no more entries than
/// the fill-reducing one's: no more memory or work, and solves that read the vector in order. The
/// trial costs one factorization more at the first call. Below that size the factor is small
/// enough for the cache and the order of its reads gains nothing (the benchmark lattice's figures
/// are in docs/benchmarks.md), so small systems keep KLU's ordering alone.
///
/// From `streamed_solve_from` entries in L and U on, the factors are also copied in the order the
/// triangular solves read them, and solves read the copy (dae/linsolve/klu_streamed_solve.hpp):
/// KLU's own layout makes each solve stream the whole factor from memory twice once it is larger
/// than the cache. The copy doubles the factor's memory, so factors that fit in a cache (2.4 MB at
/// 200,000 entries) keep klu_solve, where the copy gains nothing, and so do factors whose
/// pivoting factorization cost more than `streamed_solve_most_flops_per_entry` flops an entry
/// (KLU's count, klu_flops): there the factorizations outweigh the solves (keeps_streamed_copy,
/// models/core/memory_estimate.hpp; docs/benchmarks.md).
struct KluSettings {
  int ordering = 0;
  bool confirm_with_condest = false;
  int band_ordering_from = 50'000;
  long streamed_solve_from = kStreamedSolveFromEntries;
  double streamed_solve_most_flops_per_entry = kStreamedSolveMostFlopsPerEntry;
};
/// SUNDIALS' SUNLinSol_KLU's: COLAMD, and a small rcond confirmed by condest before pivoting
/// afresh.
inline constexpr KluSettings kSundialsKluSettings{1, true};

/// The entries of the KLU factors L and U (with those off BTF's diagonal blocks) of a matrix of
/// this pattern as KLU's symbolic analysis under AMD predicts them, from the factor of the pattern
/// of A + Aᵀ: exact for a symmetric pattern when the pivots stay on the diagonal, an upper bound
/// when they do so on an unsymmetric one; and the flops of that factorization (AMD's count).
/// Costs an analysis (AMD) and no factorization. Throws std::runtime_error when the analysis
/// fails; std::invalid_argument for a matrix not square.
struct KluFactorPrediction {
  double entries = 0;
  double flops = 0;
};
[[nodiscard]] KluFactorPrediction predicted_klu_factor(const Eigen::SparseMatrix<double>& matrix);

class FixedPatternKlu {
 public:
  explicit FixedPatternKlu(KluSettings settings = {});
  ~FixedPatternKlu();
  FixedPatternKlu(const FixedPatternKlu&) = delete;
  FixedPatternKlu& operator=(const FixedPatternKlu&) = delete;

  /// Factors `matrix` (compressed), whose pattern must be that of the first matrix factored;
  /// false when it is singular (or the analysis failed). The matrix is read during the call only.
  bool factor(const Eigen::SparseMatrix<double>& matrix);
  /// The same on a view (the integrator's values over a fixed pattern,
  /// dae/linsolve/block_jacobian.hpp).
  bool factor(const Eigen::Map<Eigen::SparseMatrix<double>>& matrix);
  /// The next factor() pivots afresh (the analysis, which depends on the pattern only, is kept).
  void restart();
  /// x ← (last matrix factored)⁻¹ x, in place.
  void solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const;
  /// x with (last matrix factored) x = rhs.
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  /// Factorizations with pivoting, and refactorizations that reused their pivots.
  [[nodiscard]] long pivoting_factorizations() const { return pivoting_; }
  [[nodiscard]] long refactorizations() const { return refactored_; }
  /// Whether the factors are in the bandwidth-reducing ordering (see KluSettings).
  [[nodiscard]] bool band_ordered() const { return band_ordered_; }
  /// Whether solves read the factors' streamed copy (see KluSettings).
  [[nodiscard]] bool streamed() const;

 private:
  struct Impl;
  bool factor(int n, const int* outer, const int* inner, const double* values);
  bool first_factor(int n, int* outer, int* inner, double* values);
  /// After a pivoting factorization: whether it succeeded; copies the factors for the streamed
  /// solve when they are large enough.
  bool copy_for_streamed_solve();
  std::unique_ptr<Impl> impl_;
  KluSettings settings_;
  long pivoting_ = 0;
  long refactored_ = 0;
  bool band_ordered_ = false;
};

/// KLU's symbolic analysis (BTF, AMD) kept while the pattern of the matrices stays, and done
/// afresh when it changes (a mechanism's KKT matrix keeps its pattern; another model's would not);
/// every factorization searches its pivots afresh, so the factors are those of a fresh KLU on
/// the matrix. For small matrices whose values vary widely between factorizations, up to
/// singularity (coordinate partitioning's KKT matrix at a mechanism's singular position: there,
/// pivots reused from earlier values changed A02's results and lost its passage, where fresh ones
/// keep them bit for bit). Keeps a copy of the pattern, compared at each factorization (O(nnz)).
class KluByPattern {
 public:
  /// Factors `matrix` (square); false when it is singular.
  bool factor(const Eigen::SparseMatrix<double>& matrix);
  /// x with (last matrix factored) x = rhs. Throws std::logic_error before a successful factor().
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  /// Analyses made: one per pattern met.
  [[nodiscard]] long analyses() const { return analyses_; }

 private:
  std::unique_ptr<FixedPatternKlu> klu_;
  std::vector<int> outer_, inner_;
  bool factored_ = false;
  long analyses_ = 0;
};

}  // namespace condyn
