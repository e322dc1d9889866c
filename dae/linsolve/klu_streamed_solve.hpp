#pragma once
/// KLU's triangular solves over a copy of its factors laid out in the order the solve reads them
/// (dae/linsolve/fixed_pattern_klu.hpp uses it for large factors). Internal to
/// fixed_pattern_klu.cpp: it includes klu.h.
///
/// Why not klu_solve: KLU stores each column's L and U entries next to each other (column k's L,
/// then its U, in one array per block), so the forward solve, which needs L only, and the
/// backward one, which needs U only, each read nearly every cache line of both: on the benchmark
/// lattice a column holds 10 to 20 entries of each, a line or two. Once the factor is larger than
/// the cache, a solve streams it from memory twice. This copy holds, per block in the order the
/// solve takes them (the last block first), L's columns ascending then U's descending, indices and
/// values in two arrays: each solve streams it once, forward. The arithmetic is klu_solve's, in
/// its order, so the results are bitwise equal. The gain grows with the factor's size beyond the
/// cache (the lattice's figures: docs/benchmarks.md). It costs the factor's memory again (12 bytes
/// per entry), which is why only large factors get it (KluSettings::streamed_solve_from).

#include <klu.h>

#include <Eigen/Core>
#include <vector>

namespace condyn {

class KluStreamedSolve {
 public:
  /// Copies the factors (indices and values) of a pivoting factorization.
  void build(const klu_symbolic& symbolic, const klu_numeric& numeric);
  /// Copies the values again after a refactorization with the same pivots (klu_refactor keeps
  /// the pattern).
  void refresh_values(const klu_symbolic& symbolic, const klu_numeric& numeric);
  /// x ← A⁻¹ x with the factors last copied, as klu_solve with one right-hand side.
  void solve(const klu_symbolic& symbolic, const klu_numeric& numeric,
             Eigen::Ref<Eigen::VectorXd> x) const;

 private:
  /// Calls visit(column) for each column of the factors in the order the solve reads them.
  template <class Visit>
  static void walk(const klu_symbolic& symbolic, const klu_numeric& numeric, Visit visit);

  std::vector<int> lengths_;  ///< per column in solve order: L's, then U's, per block
  std::vector<int> rows_;     ///< row indices within the block
  std::vector<double> values_;
  mutable std::vector<double> work_;
};

}  // namespace condyn
