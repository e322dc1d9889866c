// IDA's sparse Jacobian factored by KLU in 32-bit indices (dae/integrators/klu_linear_solver.hpp).

#include "dae/integrators/klu_linear_solver.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#include <exception>
#include <new>
#include <vector>

#include "dae/integrators/linear_solver_parts.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"

namespace condyn::sundials {

namespace {

// The matrix: a value array sized to the pattern.

struct MatrixContent {
  std::vector<double> values;
};

MatrixContent& matrix_content(SUNMatrix a) { return *static_cast<MatrixContent*>(a->content); }

SUNMatrix_ID matrix_id(SUNMatrix /*a*/) { return SUNMATRIX_CUSTOM; }

int matrix_zero(SUNMatrix a) {
  auto& values = matrix_content(a).values;
  std::fill(values.begin(), values.end(), 0.0);
  return SUNMAT_SUCCESS;
}

int matrix_space(SUNMatrix a, long* lenrw, long* leniw) {
  *lenrw = static_cast<long>(matrix_content(a).values.size());
  *leniw = 0;
  return SUNMAT_SUCCESS;
}

void matrix_destroy(SUNMatrix a) {
  if (a == nullptr) return;
  delete static_cast<MatrixContent*>(a->content);
  a->content = nullptr;
  SUNMatFreeEmpty(a);
}

// The solver.

struct Content {
  const JacobianPattern* pattern = nullptr;
  FixedPatternKlu klu{kSundialsKluSettings};
  int last_flag = 0;
};

Content& content(SUNLinearSolver s) { return content_of<Content>(s); }

SUNLinearSolver_Type get_type(SUNLinearSolver /*s*/) { return SUNLINEARSOLVER_DIRECT; }

/// At every (re)initialization of the integrator, as SUNLinSol_KLU: the next setup pivots afresh.
int initialize(SUNLinearSolver s) {
  content(s).klu.restart();
  return content(s).last_flag = SUNLS_SUCCESS;
}

int setup(SUNLinearSolver s, SUNMatrix a) {
  Content& c = content(s);
  double* values = pattern_matrix_values(a);
  if (values == nullptr ||
      matrix_content(a).values.size() != static_cast<std::size_t>(c.pattern->nonZeros())) {
    return c.last_flag = SUNLS_ILL_INPUT;
  }
  try {
    // A singular matrix is recoverable: IDA retries the step with a smaller one (another cj).
    if (!c.klu.factor(c.pattern->map(values))) {
      return c.last_flag = SUNLS_PACKAGE_FAIL_REC;
    }
  } catch (const std::bad_alloc&) {
    return c.last_flag = SUNLS_MEM_FAIL;
  } catch (const std::exception&) {
    return c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  return c.last_flag = SUNLS_SUCCESS;
}

int solve(SUNLinearSolver s, SUNMatrix /*a*/, N_Vector x, N_Vector b, double /*tol*/) {
  Content& c = content(s);
  return c.last_flag = solve_into(x, b, [&c](auto& values) { c.klu.solve_in_place(values); });
}

}  // namespace

SUNMatrix make_pattern_matrix(const JacobianPattern& pattern, SUNContext ctx) {
  SUNMatrix a = SUNMatNewEmpty(ctx);
  if (a == nullptr) return nullptr;
  try {
    a->content =
        new MatrixContent{std::vector<double>(static_cast<std::size_t>(pattern.nonZeros()))};
  } catch (const std::bad_alloc&) {
    SUNMatFreeEmpty(a);
    return nullptr;
  }
  a->ops->getid = matrix_id;
  a->ops->zero = matrix_zero;
  a->ops->space = matrix_space;
  a->ops->destroy = matrix_destroy;
  return a;
}

double* pattern_matrix_values(SUNMatrix a) {
  if (a == nullptr || a->ops == nullptr || a->ops->getid != matrix_id) return nullptr;
  return matrix_content(a).values.data();
}

SUNLinearSolver make_klu_solver(const JacobianPattern& pattern, SUNContext ctx) {
  SUNLinearSolver s = new_solver_with<Content>(ctx, &pattern);
  if (s == nullptr) return nullptr;
  s->ops->gettype = get_type;
  s->ops->initialize = initialize;
  s->ops->setup = setup;
  s->ops->solve = solve;
  return s;
}

}  // namespace condyn::sundials
