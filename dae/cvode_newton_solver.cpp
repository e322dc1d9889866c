// CVODE's Newton systems solved by the problem (dae/cvode_newton_solver.hpp).

#include "dae/cvode_newton_solver.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>

#include <cmath>
#include <exception>
#include <new>

namespace condyn::sundials {

namespace {

constexpr double kMaxGammaRatioChange = 0.3;

struct Content {
  NewtonSystem* system = nullptr;
  void* cvode_mem = nullptr;
  double gamma_setup = 0.0;
  long setups = 0;
  int last_flag = 0;
};

Content& content(SUNLinearSolver s) { return *static_cast<Content*>(s->content); }

SUNLinearSolver_Type get_type(SUNLinearSolver /*s*/) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }

int initialize(SUNLinearSolver /*s*/) { return SUNLS_SUCCESS; }

/// Factors for γ (the problem's setup).
int factor_at(Content& c, double gamma) {
  try {
    ++c.setups;
    // A singular matrix is recoverable: CVODE retries the step with a smaller one (another γ).
    if (!c.system->setup(gamma)) return c.last_flag = SUNLS_PACKAGE_FAIL_REC;
  } catch (const std::bad_alloc&) {
    return c.last_flag = SUNLS_MEM_FAIL;
  } catch (const std::exception&) {
    return c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  c.gamma_setup = gamma;
  return c.last_flag = SUNLS_SUCCESS;
}

int setup(SUNLinearSolver s, SUNMatrix /*a*/) {
  Content& c = content(s);
  double gamma = 0.0;
  if (CVodeGetCurrentGamma(c.cvode_mem, &gamma) != CV_SUCCESS) return c.last_flag = SUNLS_MEM_NULL;
  return factor_at(c, gamma);
}

int solve(SUNLinearSolver s, SUNMatrix /*a*/, N_Vector x, N_Vector b, double /*tol*/) {
  Content& c = content(s);
  // CVODE 6.4 never calls the setup of a solver without a matrix or a preconditioner (its
  // cvLsInitialize sets lsetup to NULL): factor here when nothing is factored yet or γ has moved
  // by more than CVODE's own threshold for a new matrix (dgmax_lsetup, 0.3).
  double gamma = 0.0;
  if (CVodeGetCurrentGamma(c.cvode_mem, &gamma) != CV_SUCCESS) return c.last_flag = SUNLS_MEM_NULL;
  if (c.gamma_setup == 0.0 || std::abs(gamma / c.gamma_setup - 1.0) > kMaxGammaRatioChange) {
    if (const int flag = factor_at(c, gamma); flag != SUNLS_SUCCESS) return flag;
  }
  N_VScale(1.0, b, x);
  Eigen::Map<Eigen::VectorXd> view(N_VGetArrayPointer(x),
                                   static_cast<Eigen::Index>(N_VGetLength(x)));
  try {
    c.system->solve(view);
  } catch (const std::exception&) {
    return c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  if (gamma != c.gamma_setup) view *= 2.0 / (1.0 + gamma / c.gamma_setup);
  return c.last_flag = view.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
}

sunindextype last_flag(SUNLinearSolver s) { return content(s).last_flag; }

int free_solver(SUNLinearSolver s) {
  if (s == nullptr) return SUNLS_SUCCESS;
  delete static_cast<Content*>(s->content);
  s->content = nullptr;
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver make_newton_solver(NewtonSystem& system, void* cvode_mem, SUNContext ctx) {
  SUNLinearSolver s = SUNLinSolNewEmpty(ctx);
  if (s == nullptr) return nullptr;
  s->content = new (std::nothrow) Content{&system, cvode_mem};
  if (s->content == nullptr) {
    SUNLinSolFreeEmpty(s);
    return nullptr;
  }
  s->ops->gettype = get_type;
  s->ops->initialize = initialize;
  s->ops->setup = setup;
  s->ops->solve = solve;
  s->ops->lastflag = last_flag;
  s->ops->free = free_solver;
  return s;
}

long newton_solver_setups(SUNLinearSolver solver) { return content(solver).setups; }

}  // namespace condyn::sundials
