#pragma once
/// A bandwidth-reducing ordering for KLU's factorizations (dae/linsolve/fixed_pattern_klu.hpp):
/// reverse Cuthill–McKee on the symmetric pattern of A + Aᵀ, and the number of entries a factor of
/// that pattern has under it. Where a model's mesh is long and thin (a strip, a frame, a chain),
/// such an ordering keeps as few factor entries as the fill-reducing ones (COLAMD, AMD) while each
/// column of the factor touches rows close to its own: the triangular solves then walk the
/// solution vector in order instead of across it. On the benchmark lattice's index-1 Newton
/// matrix at 10⁵ DOFs and more, whose factor is far larger than the cache, a solve takes markedly
/// less time per factor entry (figures in docs/benchmarks.md).
///
/// Written here: neither SuiteSparse nor Eigen, the project's sparse libraries, has a
/// bandwidth-reducing ordering (they order for fill: AMD, COLAMD, CAMD, METIS's nested
/// dissection).

#include <vector>

namespace condyn {

/// The pattern of A + Aᵀ for a square compressed-column matrix A of size n: for each column, the
/// rows of its other entries, sorted, the diagonal left out.
struct SymmetricPattern {
  int size = 0;
  std::vector<long> outer;  // size + 1
  std::vector<int> inner;
};
[[nodiscard]] SymmetricPattern symmetric_pattern(int n, const int* outer, const int* inner);

/// order[k] is the index placed k-th: reverse Cuthill–McKee, each connected component started at a
/// pseudo-peripheral vertex (George and Liu's search: from a vertex of least degree, repeatedly to
/// a least-degree vertex of the farthest level while the eccentricity grows), neighbours visited
/// by increasing degree.
[[nodiscard]] std::vector<int> reverse_cuthill_mckee(const SymmetricPattern& pattern);

/// The entries strictly below the diagonal of the Cholesky factor of a matrix with `pattern`
/// (and nonzero diagonal) with rows and columns taken in `order`, counted on the elimination tree
/// in time proportional to that count; `limit` + 1 as soon as the count passes `limit`.
[[nodiscard]] long cholesky_entries_below_diagonal(const SymmetricPattern& pattern,
                                                   const std::vector<int>& order, long limit);

}  // namespace condyn
