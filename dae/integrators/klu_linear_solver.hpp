#pragma once
/// A SUNDIALS matrix-based linear solver that factors the integrator's sparse Jacobian with KLU in
/// 32-bit indices, over the problem's fixed pattern (dae/linsolve/block_jacobian.hpp), for IDA's
/// Newton iterations. SUNDIALS' own SUNLinSol_KLU calls KLU in sunindextype, 64 bits in Debian's
/// build: its factors take 16 bytes an entry instead of 12, and on the benchmark lattice's index-1
/// Newton matrix its triangular solves take longer than KLU's 32-bit ones, the more so the larger
/// the matrix (`condyn_bare_driver DIR --klu-index-width 9`, docs/benchmarks.md; issue 12).
/// Everything else is SUNLinSol_KLU's (dae/linsolve/fixed_pattern_klu.hpp): COLAMD ordering; a
/// pivoting factorization at the first setup after each (re)initialization, refactorizations with
/// the pivots kept after; a pivoting one again when KLU's rcond estimate falls below ε^(2/3) and
/// its condest confirms a condition number above 1/ε^(2/3). SUNDIALS types stay inside dae/.

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include "dae/linsolve/block_jacobian.hpp"

namespace condyn::sundials {

/// The integrator's Newton matrix for this solver: the Jacobian's values in `pattern`, and no index
/// arrays of its own (a SUNSparseMatrix holds them again, in 64 bits, memory that nothing
/// reads). IDA zeroes it (SUNMatZero) before each Jacobian evaluation, the Jacobian
/// callback fills pattern_matrix_values(), the solver's setup factors them. Returns nullptr when
/// out of memory.
[[nodiscard]] SUNMatrix make_pattern_matrix(const JacobianPattern& pattern, SUNContext ctx);
/// The values of a make_pattern_matrix() matrix (pattern.nonZeros() of them); nullptr for any
/// other matrix.
[[nodiscard]] double* pattern_matrix_values(SUNMatrix a);

/// The solver keeps a pointer to `pattern` (which must outlive it); its matrix is a
/// make_pattern_matrix() matrix on the same pattern. Returns nullptr when out of memory.
[[nodiscard]] SUNLinearSolver make_klu_solver(const JacobianPattern& pattern, SUNContext ctx);

}  // namespace condyn::sundials
