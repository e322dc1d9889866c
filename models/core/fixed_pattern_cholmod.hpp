#pragma once
/// CHOLMOD (SuiteSparse) on a sequence of symmetric positive-definite matrices that share one
/// pattern: the symbolic analysis once, under the fill-reducing ordering with the fewest entries
/// in L among those the library was built with (AMD, METIS, CHOLMOD's nested dissection), then
/// numeric factorizations L Lᵀ = P A Pᵀ that reuse it (cholmod_factorize: no ordering, no
/// symbolic work). Supernodal where CHOLMOD finds it pays (its default rule: flops per entry of L
/// at least 40, as on 2D and 3D meshes), its dense blocks through OpenBLAS. CHOLMOD and OpenBLAS
/// are loaded with dlopen on first use (models/core/load_library.hpp): the first analysis or
/// FixedPatternCholmod throws LibraryUnavailable when either cannot be loaded. Only the lower
/// triangle is read: the matrix is given whole (both triangles, as CondensedNewton forms it) and
/// must be symmetric. CHOLMOD stays out of the header.

#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

namespace condyn {

/// One fill-reducing ordering's symbolic analysis of a pattern: the name (`amd`, `metis`,
/// `nesdis`), the entries of L, the flops of a factorization (CHOLMOD's count for a simplicial
/// L Lᵀ) and the factor's memory in bytes (values and indices, supernodal or simplicial as
/// CHOLMOD would factor it).
struct CholmodCandidate {
  std::string ordering;
  double factor_entries = 0.0;
  double flops = 0.0;
  double factor_bytes = 0.0;
};

/// The symbolic analysis of `matrix` (square, compressed, both triangles stored) under every
/// ordering the library offers, in the order AMD, METIS, NESDIS (an ordering missing from the
/// build is left out). Costs one analysis per ordering and no factorization. Throws
/// std::invalid_argument for a matrix not square; LibraryUnavailable when CHOLMOD or OpenBLAS
/// cannot be loaded; std::runtime_error when every analysis fails.
[[nodiscard]] std::vector<CholmodCandidate> cholmod_candidates(
    const Eigen::SparseMatrix<double>& matrix);

/// The candidate with the fewest entries in L (the first of equals); `candidates` not empty.
[[nodiscard]] const CholmodCandidate& least_fill(const std::vector<CholmodCandidate>& candidates);

/// Supernodal factors with at least this many values (L's blocks, CHOLMOD's xsize) are solved
/// by condyn's two-lane sweeps (models/core/supernodal_solve.hpp), smaller ones and simplicial
/// ones by CHOLMOD's own solve: below it a solve takes well under a millisecond and the
/// hand-over to a second thread costs more than it saves (docs/benchmarks.md).
inline constexpr double kOwnSolveFewestEntries = 1e6;
/// ... unless the supernodes above the two lanes' subtrees, which one thread sweeps alone, hold
/// more than this share of the factor: on a 3D mesh the top separators' dense blocks (a fifth of
/// the factor at 10⁵ DOFs) are where OpenBLAS's blocked, threaded kernels in CHOLMOD's solve win
/// (docs/benchmarks.md).
inline constexpr double kOwnSolveMostShared = 0.1;

class FixedPatternCholmod {
 public:
  /// The symbolic analysis under `ordering` alone (`amd`, `metis` or `nesdis`: the least fill
  /// that cholmod_candidates found, so that a run does not analyse the pattern twice under every
  /// ordering), or, when it is empty, under each ordering of the build, keeping the least fill.
  /// Loads CHOLMOD when no earlier call has. Throws LibraryUnavailable when it cannot be loaded,
  /// std::invalid_argument for an ordering not among the three. Solves use condyn's two-lane
  /// sweeps on supernodal factors of at least `own_solve_fewest_entries` values whose shared
  /// supernodes hold at most `own_solve_most_shared` of them.
  explicit FixedPatternCholmod(std::string ordering = {},
                               double own_solve_fewest_entries = kOwnSolveFewestEntries,
                               double own_solve_most_shared = kOwnSolveMostShared);
  ~FixedPatternCholmod();
  FixedPatternCholmod(const FixedPatternCholmod&) = delete;
  FixedPatternCholmod& operator=(const FixedPatternCholmod&) = delete;

  /// Factors `matrix` (compressed, symmetric, both triangles), whose pattern must be that of the
  /// first matrix factored; the first call analyses it under the least-fill ordering. False when
  /// the matrix is not positive definite (a recoverable failure: the integrator retries with a
  /// smaller step, where cj² M dominates). Throws std::invalid_argument for a matrix not square
  /// or of another size than the first, std::runtime_error when CHOLMOD fails otherwise
  /// (out of memory).
  bool factor(const Eigen::SparseMatrix<double>& matrix);
  /// The smallest pivot of the last factorization over the largest: (min lᵢᵢ / max lᵢᵢ)², the
  /// ratio of the pivots dᵢ of A = L D Lᵀ (CHOLMOD's cholmod_rcond; a rough reciprocal condition
  /// number, 0 when a pivot is zero). Throws std::logic_error before a factorization.
  [[nodiscard]] double pivot_ratio() const;
  /// x ← (last matrix factored)⁻¹ x, in place. Throws std::logic_error before a factorization.
  void solve_in_place(Eigen::Ref<Eigen::VectorXd> x);
  /// The ordering named at construction, or the one the analysis chose (empty before the first
  /// factor()).
  [[nodiscard]] const std::string& ordering() const { return ordering_; }
  /// Symbolic analyses made: one per ordering tried, at the first factor() only.
  [[nodiscard]] int analyses() const { return analyses_; }
  /// Numeric factorizations made (all reuse the one symbolic analysis).
  [[nodiscard]] long factorizations() const { return factorizations_; }
  /// Whether the factor is supernodal (false before the first factor()).
  [[nodiscard]] bool supernodal() const;
  /// The lanes of condyn's own solve (1 or 2), or 0 when CHOLMOD's solve serves (a simplicial or
  /// small factor, or before the first factor()).
  [[nodiscard]] int solve_lanes() const;

 private:
  struct Impl;
  void analyze(const Eigen::SparseMatrix<double>& matrix);
  std::unique_ptr<Impl> impl_;
  std::string ordering_;
  double own_solve_fewest_entries_, own_solve_most_shared_;
  int analyses_ = 0;
  long factorizations_ = 0;
};

}  // namespace condyn
