#pragma once
/// A SUNDIALS matrix-based linear solver that factors the integrator's sparse Jacobian with KLU in
/// 32-bit indices, over the problem's fixed pattern (dae/block_jacobian.hpp), for IDA's Newton
/// iterations. SUNDIALS' own SUNLinSol_KLU calls KLU in sunindextype, 64 bits in Debian's build:
/// its factors take 16 bytes an entry instead of 12, and on the benchmark lattice's index-1 Newton
/// matrix its triangular solves took 2.3 times as long as KLU's 32-bit ones (10⁴ and 10⁵ DOFs,
/// issue 12). Everything else is SUNLinSol_KLU's (dae/fixed_pattern_klu.hpp): COLAMD ordering; a
/// pivoting factorization at the first setup after each (re)initialization, refactorizations
/// with the pivots kept after; a pivoting one again when KLU's rcond estimate falls below ε^(2/3)
/// and its condest confirms a condition number above 1/ε^(2/3). SUNDIALS types stay inside dae/.

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include "dae/block_jacobian.hpp"

namespace condyn::sundials {

/// The solver keeps a pointer to `pattern` (which must outlive it). The integrator's matrix must
/// be a SUNSparseMatrix (CSC) whose values array holds the Jacobian in that pattern, as the
/// Jacobian callback fills it. Returns nullptr when out of memory.
[[nodiscard]] SUNLinearSolver make_klu_solver(const JacobianPattern& pattern, SUNContext ctx);

}  // namespace condyn::sundials
