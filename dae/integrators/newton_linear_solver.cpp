// Newton systems solved by the problem (dae/integrators/newton_linear_solver.hpp).

#include "dae/integrators/newton_linear_solver.hpp"

#include "dae/integrators/linear_solver_parts.hpp"
#include "dae/interface/recoverable_error.hpp"

#include <nvector/nvector_serial.h>

#include <cmath>
#include <exception>
#include <new>
#include <utility>

namespace condyn::sundials {

namespace {

struct Content {
  NewtonSystem* system = nullptr;
  std::function<bool(double&)> current;
  double max_change = 0.0;  ///< relative change of the scalar that triggers a new factorization
  NewtonState state;        ///< empty unless the system is state-dependent
  double gamma_setup = 0.0;
  long setups = 0;
  long step_at_setup = 0;  ///< the integrator's step count at the last factorization
  int last_flag = 0;
};

Content& content(SUNLinearSolver s) { return content_of<Content>(s); }

SUNLinearSolver_Type get_type(SUNLinearSolver /*s*/) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }

int initialize(SUNLinearSolver /*s*/) { return SUNLS_SUCCESS; }

/// Gives a state-dependent system the integrator's state; false when the integrator cannot tell.
bool linearize(Content& c) {
  double t = 0.0;
  N_Vector y = nullptr;
  if (!c.state || !c.state(t, y, c.step_at_setup) || y == nullptr) return false;
  c.system->linearize_at(t, view(y));
  return true;
}

/// Whether a state-dependent system's matrix is due for renewal at this solve.
bool stale(Content& c) {
  if (!c.system->state_dependent()) return false;
  double t = 0.0;
  N_Vector y = nullptr;
  long steps = 0;
  if (!c.state || !c.state(t, y, steps)) return false;
  // Fewer steps than at the setup: the integrator restarted (a load step).
  return steps < c.step_at_setup || steps - c.step_at_setup >= kStepsBetweenSetups;
}

/// Factors for γ (the problem's setup), linearised at the integrator's state first when the
/// matrix depends on it.
int factor_at(Content& c, double gamma) {
  try {
    ++c.setups;
    if (c.system->state_dependent() && !linearize(c)) return c.last_flag = SUNLS_MEM_NULL;
    // A singular matrix is recoverable: CVODE retries the step with a smaller one (another γ).
    if (!c.system->setup(gamma)) return c.last_flag = SUNLS_PACKAGE_FAIL_REC;
  } catch (const std::bad_alloc&) {
    return c.last_flag = SUNLS_MEM_FAIL;
  } catch (const RecoverableError&) {  // a singular KKT matrix at a trial state
    return c.last_flag = SUNLS_PACKAGE_FAIL_REC;
  } catch (const std::exception&) {
    return c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  c.gamma_setup = gamma;
  return c.last_flag = SUNLS_SUCCESS;
}

int setup(SUNLinearSolver s, SUNMatrix /*a*/) {
  Content& c = content(s);
  double gamma = 0.0;
  if (!c.current(gamma)) return c.last_flag = SUNLS_MEM_NULL;
  return factor_at(c, gamma);
}

int solve(SUNLinearSolver s, SUNMatrix /*a*/, N_Vector x, N_Vector b, double /*tol*/) {
  Content& c = content(s);
  // SUNDIALS 6.4 never calls the setup of a solver without a matrix or a preconditioner: factor
  // here when nothing is factored yet or the scalar has moved by more than max_change.
  double gamma = 0.0;
  if (!c.current(gamma)) return c.last_flag = SUNLS_MEM_NULL;
  if (c.gamma_setup == 0.0 || std::abs(gamma / c.gamma_setup - 1.0) > c.max_change || stale(c)) {
    if (const int flag = factor_at(c, gamma); flag != SUNLS_SUCCESS) return flag;
  }
  return c.last_flag = solve_into(x, b, [&c, gamma](auto& values) {
           c.system->solve(values);
           if (gamma != c.gamma_setup) values *= 2.0 / (1.0 + gamma / c.gamma_setup);
         });
}

}  // namespace

SUNLinearSolver make_newton_solver(NewtonSystem& system, std::function<bool(double&)> current,
                                   double max_change, SUNContext ctx, NewtonState state) {
  SUNLinearSolver s =
      new_solver_with<Content>(ctx, &system, std::move(current), max_change, std::move(state));
  if (s == nullptr) return nullptr;
  s->ops->gettype = get_type;
  s->ops->initialize = initialize;
  s->ops->setup = setup;
  s->ops->solve = solve;
  return s;
}

long newton_solver_setups(SUNLinearSolver solver) { return content(solver).setups; }

}  // namespace condyn::sundials
