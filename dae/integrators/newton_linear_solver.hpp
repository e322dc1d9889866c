#pragma once
/// A SUNDIALS linear solver (matrix-embedded: the integrator passes it no matrix) over a problem's
/// own NewtonSystem, for CVODE's BDF Newton iteration (scalar γ: I − γ ∂F/∂y) and IDA's (scalar
/// cj: ∂F/∂y + cj ∂F/∂y'). SUNDIALS types stay inside dae/.

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include <functional>

#include "dae/linsolve/newton_system.hpp"

namespace condyn::sundials {

/// The solver keeps a pointer to `system` (which must outlive it) and asks `current` for the
/// integrator's current scalar (CVodeGetCurrentGamma, IDAGetCurrentCj; false when it cannot).
/// It factors for the current scalar when asked to set up and, since SUNDIALS 6.4 never asks a
/// solver without a matrix or preconditioner (cvLsInitialize and idaLsInitialize set lsetup to
/// NULL), whenever a solve finds the scalar moved by more than `max_change` (relative) from the
/// factored one; a solve at another scalar than the factored one is scaled by
/// 2 / (1 + c/c_setup), as both integrators scale the solves of their matrix-based solvers (they
/// do not for matrix-embedded ones). max_change 0: every solve is exact (a new factorization
/// whenever the scalar changes). Returns nullptr when out of memory.
///
/// A state-dependent system (NewtonSystem::state_dependent) needs `state`: the integrator's time,
/// predicted state and step count (false when it cannot tell). Each factorization then linearises
/// at that state first, and a solve also refactors once kStepsBetweenSetups steps have passed
/// since the last one (SUNDIALS' own matrix-based solvers renew their matrix at most that many
/// steps apart; a Newton iteration that fails to converge shrinks the step, which moves the
/// scalar and so renews the matrix too).
using NewtonState = std::function<bool(double& t, N_Vector& y, long& steps)>;
[[nodiscard]] SUNLinearSolver make_newton_solver(NewtonSystem& system,
                                                 std::function<bool(double&)> current,
                                                 double max_change, SUNContext ctx,
                                                 NewtonState state = {});

/// CVODE's default largest number of steps between two setups of its linear solver (msbp).
inline constexpr long kStepsBetweenSetups = 20;

/// Setups (factorizations) the solver has made: the integrators count no Jacobian evaluations.
[[nodiscard]] long newton_solver_setups(SUNLinearSolver solver);

}  // namespace condyn::sundials
