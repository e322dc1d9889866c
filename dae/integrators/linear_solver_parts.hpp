#pragma once
/// What condyn's SUNDIALS linear solvers (dae/newton_linear_solver, dae/klu_linear_solver) share:
/// creating a solver around its own content, freeing it, its last flag, and a solve of x = A⁻¹ b
/// in place in x. SUNDIALS types stay inside dae/.

#include <sundials/sundials_linearsolver.h>

#include <exception>
#include <new>
#include <utility>

#include "dae/integrators/sundials_raii.hpp"

namespace condyn::sundials {

/// The solver's `Content` (which has an int `last_flag`).
template <class Content>
Content& content_of(SUNLinearSolver s) {
  return *static_cast<Content*>(s->content);
}

template <class Content>
sunindextype last_flag_of(SUNLinearSolver s) {
  return content_of<Content>(s).last_flag;
}

template <class Content>
int free_solver_of(SUNLinearSolver s) {
  if (s == nullptr) return SUNLS_SUCCESS;
  delete static_cast<Content*>(s->content);
  s->content = nullptr;
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

/// An empty solver holding a new Content{args...}, with its lastflag and free operations set (the
/// caller sets gettype, initialize, setup and solve); nullptr when out of memory.
template <class Content, class... Args>
SUNLinearSolver new_solver_with(SUNContext ctx, Args&&... args) {
  SUNLinearSolver s = SUNLinSolNewEmpty(ctx);
  if (s == nullptr) return nullptr;
  try {
    s->content = new Content{std::forward<Args>(args)...};
  } catch (const std::bad_alloc&) {
    SUNLinSolFreeEmpty(s);
    return nullptr;
  }
  s->ops->lastflag = last_flag_of<Content>;
  s->ops->free = free_solver_of<Content>;
  return s;
}

/// x ← b, then solve(view of x) in place: SUNLS_SUCCESS, SUNLS_PACKAGE_FAIL_REC for a non-finite
/// solution (the integrator retries with a smaller step), SUNLS_PACKAGE_FAIL_UNREC when `solve`
/// throws.
template <class Solve>
int solve_into(N_Vector x, N_Vector b, Solve&& solve) {
  N_VScale(1.0, b, x);
  auto values = view(x);
  try {
    solve(values);
  } catch (const std::exception&) {
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
  return values.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
}

}  // namespace condyn::sundials
