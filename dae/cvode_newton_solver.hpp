#pragma once
/// A SUNDIALS linear solver (matrix-embedded: CVODE passes it no matrix) over an OdeProblem's own
/// NewtonSystem, for CVODE's BDF Newton iteration. SUNDIALS types stay inside dae/.

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include "dae/ode_problem.hpp"

namespace condyn::sundials {

/// The solver keeps pointers to `system` and to the CVODE memory (for the current γ): both must
/// outlive it. It factors for CVODE's current γ when asked to set up and, since CVODE 6.4 never
/// asks a solver without a matrix, whenever a solve finds γ moved by more than 30% from the
/// factored one; a solve at another γ than the factored one is scaled by 2 / (1 + γ/γ_setup), as
/// CVODE scales the solves of its matrix-based solvers (it does not for matrix-embedded ones).
/// Returns nullptr when out of memory.
[[nodiscard]] SUNLinearSolver make_newton_solver(NewtonSystem& system, void* cvode_mem,
                                                 SUNContext ctx);

/// Setups (factorizations) the solver has made: CVODE counts no Jacobian evaluations for it.
[[nodiscard]] long newton_solver_setups(SUNLinearSolver solver);

}  // namespace condyn::sundials
