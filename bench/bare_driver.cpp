// The benchmark's floor (issue 12, item 5): a bare SUNDIALS IDA + KLU driver, no condyn code, that
// solves the index-1 (acceleration-level) constrained system read from Matrix Market files
//   u' = v,   M v' = s(t) f - K u - A^T lambda,   A v' = 0,
// y = [u; v; lambda], with s(t) the unit step, u(0) = v(0) = 0, consistent v'(0) and lambda(0) by
// IDACalcIC, scalar tolerances rtol/atol with the multipliers left out of the error test, and the
// Newton matrix dF/dy + cj dF/dy' filled by hand into a CSC matrix factored by KLU.
//
//   condyn_bare_driver DIR [--t-end T] [--output-step H] [--rtol R] [--atol A]
// reads DIR/M.mtx, DIR/K.mtx, DIR/A.mtx, DIR/f.mtx (the flags default to bench/lattice.py's
// defaults; bench/run_bench.py passes the scene's) and prints one line of key=value figures:
//   steps, residual and Jacobian evaluations, Newton iterations, failures, the wall time of the
//   solver loop (IDACalcIC to t_end), of the whole process, and the peak RSS (getrusage).
//
//   condyn_bare_driver DIR --klu-index-width SOLVES
// integrates nothing: it fills the same Newton matrix at cj = 1000, factors it with KLU as
// SUNLinSol_KLU does (COLAMD) in 64-bit indices (klu_l_*, what Debian's SUNDIALS calls) and in
// 32-bit ones (klu_*, what condyn calls), and prints the factors' entries and the median time of
// SOLVES triangular solves of each (why condyn has its own KLU solver,
// dae/integrators/klu_linear_solver.hpp).
#include <ida/ida.h>
#include <klu.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bare_common.hpp"

namespace {

using bare::check;
using bare::Clock;
using bare::cpu_seconds;
using bare::Csc;
using bare::gaxpy;
using bare::seconds_since;
using bare::transpose;

struct Problem {
  Csc M, K, A, At;
  std::vector<double> f;
  long n = 0, m = 0;
  long residuals = 0;  // our own count, beside IDA's (which leaves out the Jacobian's none)
};

int residual(double t, N_Vector yy, N_Vector yp, N_Vector rr, void* user) {
  const auto& p = *static_cast<Problem*>(user);
  const double* y = N_VGetArrayPointer(yy);
  const double* d = N_VGetArrayPointer(yp);
  double* r = N_VGetArrayPointer(rr);
  const long n = p.n;
  bare::second_order_residual(p.M, p.K, p.f, t, y, d, r);
  double* r2 = r + n;
  gaxpy(p.At, y + 2 * n, 1.0, r2);
  double* r3 = r + 2 * n;
  std::fill(r3, r3 + p.m, 0.0);
  gaxpy(p.A, d + n, 1.0, r3);
  return 0;
}

// J = dF/dy + cj dF/dy':  [cj I, -I, 0; K, cj M, A^T; 0, cj A, 0], filled column by column.
int jacobian(double, double cj, N_Vector, N_Vector, N_Vector, SUNMatrix J, void* user, N_Vector,
             N_Vector, N_Vector) {
  const auto& p = *static_cast<Problem*>(user);
  sunindextype* ptr = SUNSparseMatrix_IndexPointers(J);
  sunindextype* row = SUNSparseMatrix_IndexValues(J);
  double* val = SUNSparseMatrix_Data(J);
  const long n = p.n;
  sunindextype at = 0;
  auto put = [&](long r, double v) {
    row[at] = static_cast<sunindextype>(r);
    val[at] = v;
    ++at;
  };
  for (long c = 0; c < n; ++c) {  // u columns
    ptr[c] = at;
    put(c, cj);
    for (long k = p.K.ptr[c]; k < p.K.ptr[c + 1]; ++k) put(n + p.K.idx[k], p.K.val[k]);
  }
  for (long c = 0; c < n; ++c) {  // v columns
    ptr[n + c] = at;
    put(c, -1.0);
    for (long k = p.M.ptr[c]; k < p.M.ptr[c + 1]; ++k) put(n + p.M.idx[k], cj * p.M.val[k]);
    for (long k = p.A.ptr[c]; k < p.A.ptr[c + 1]; ++k) put(2 * n + p.A.idx[k], cj * p.A.val[k]);
  }
  for (long c = 0; c < p.m; ++c) {  // lambda columns: A^T
    ptr[2 * n + c] = at;
    for (long k = p.At.ptr[c]; k < p.At.ptr[c + 1]; ++k) put(n + p.At.idx[k], p.At.val[k]);
  }
  ptr[2 * n + p.m] = at;
  return 0;
}

/// Median of `solves` solves of the factored matrix, in seconds (b = 1 before each).
template <class Solve>
double median_solve(long size, long solves, Solve solve) {
  std::vector<double> b(static_cast<std::size_t>(size)), times;
  for (long r = 0; r < solves; ++r) {
    std::fill(b.begin(), b.end(), 1.0);
    const auto t0 = Clock::now();
    solve(b.data());
    times.push_back(seconds_since(t0));
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

/// --klu-index-width: the Newton matrix at cj = 1000 factored and solved by KLU in 64-bit and in
/// 32-bit indices, the same ordering (COLAMD, SUNLinSol_KLU's) and the same values.
void compare_klu_index_width(Problem& p, long nnz, long solves) {
  const long size = 2 * p.n + p.m;
  SUNContext ctx = nullptr;
  check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  SUNMatrix J = SUNSparseMatrix(size, size, nnz, CSC_MAT, ctx);
  if (!J) throw std::runtime_error("SUNSparseMatrix failed");
  jacobian(0.0, 1000.0, nullptr, nullptr, nullptr, J, &p, nullptr, nullptr, nullptr);
  // Debian's sunindextype is KLU's SuiteSparse_long (both long): SUNLinSol_KLU passes them as is.
  SuiteSparse_long* lp = SUNSparseMatrix_IndexPointers(J);
  SuiteSparse_long* li = SUNSparseMatrix_IndexValues(J);
  double* x = SUNSparseMatrix_Data(J);
  const std::vector<int> ip(lp, lp + size + 1), ii(li, li + lp[size]);

  klu_l_common cl;
  klu_l_defaults(&cl);
  cl.ordering = 1;
  klu_l_symbolic* sl = klu_l_analyze(size, lp, li, &cl);
  klu_l_numeric* nl = sl ? klu_l_factor(lp, li, x, sl, &cl) : nullptr;
  klu_common ci;
  klu_defaults(&ci);
  ci.ordering = 1;
  klu_symbolic* si = klu_analyze(static_cast<int>(size), const_cast<int*>(ip.data()),
                                 const_cast<int*>(ii.data()), &ci);
  klu_numeric* ni =
      si ? klu_factor(const_cast<int*>(ip.data()), const_cast<int*>(ii.data()), x, si, &ci)
         : nullptr;
  if (!nl || !ni) throw std::runtime_error("KLU could not factor the Newton matrix");
  const double t64 =
      median_solve(size, solves, [&](double* b) { klu_l_solve(sl, nl, size, 1, b, &cl); });
  const double t32 = median_solve(
      size, solves, [&](double* b) { klu_solve(si, ni, static_cast<int>(size), 1, b, &ci); });
  std::printf(
      "klu_index_width: unknowns=%ld nnz_jac=%ld lu_entries_64=%ld lu_entries_32=%ld solves=%ld "
      "solve_ms_64=%.4g solve_ms_32=%.4g ratio_32_to_64=%.3f\n",
      size, nnz, static_cast<long>(nl->lnz + nl->unz), static_cast<long>(ni->lnz + ni->unz), solves,
      1e3 * t64, 1e3 * t32, t32 / t64);
  klu_l_free_numeric(&nl, &cl);
  klu_l_free_symbolic(&sl, &cl);
  klu_free_numeric(&ni, &ci);
  klu_free_symbolic(&si, &ci);
  SUNMatDestroy(J);
  SUNContext_Free(&ctx);
}

}  // namespace

int main(int argc, char** argv) {
  const auto process_start = Clock::now();
  if (argc < 2) {
    std::cerr
        << "usage: condyn_bare_driver DIR [--t-end T] [--output-step H] [--rtol R] [--atol A]\n"
           "       condyn_bare_driver DIR --klu-index-width SOLVES\n";
    return 2;
  }
  const std::string dir = argv[1];
  double t_end = 1.0, output_step = 0.01, rtol = 1e-6, atol = 1e-8;
  double klu_solves = 0.0;
  if (!bare::parse_number_flags(argc, argv, 2,
                                {{"--t-end", {&t_end}},
                                 {"--output-step", {&output_step}},
                                 {"--rtol", {&rtol}},
                                 {"--atol", {&atol}},
                                 {"--klu-index-width", {&klu_solves}}}))
    return 2;
  try {
    Problem p;
    bare::MatrixFiles files = bare::read_matrix_files(dir);
    p.M = std::move(files.M);
    p.K = std::move(files.K);
    p.A = std::move(files.A);
    p.f = std::move(files.f);
    p.n = p.M.rows;
    p.m = p.A.rows;
    p.At = transpose(p.A);
    const long n = p.n, m = p.m, size = 2 * n + m;
    const long nnz = n + static_cast<long>(p.K.idx.size()) + n + static_cast<long>(p.M.idx.size()) +
                     2 * static_cast<long>(p.A.idx.size());
    if (klu_solves > 0.0) {
      compare_klu_index_width(p, nnz, std::lround(klu_solves));
      return 0;
    }

    const auto solver_start = Clock::now();
    const double solver_cpu_start = cpu_seconds();
    SUNContext ctx = nullptr;
    check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
    N_Vector y = N_VNew_Serial(size, ctx), yp = N_VNew_Serial(size, ctx),
             id = N_VNew_Serial(size, ctx);
    if (!y || !yp || !id) throw std::runtime_error("N_VNew_Serial failed");
    N_VConst(0.0, y);
    N_VConst(0.0, yp);
    double* idv = N_VGetArrayPointer(id);
    for (long i = 0; i < size; ++i) idv[i] = i < 2 * n ? 1.0 : 0.0;
    SUNMatrix J = SUNSparseMatrix(size, size, nnz, CSC_MAT, ctx);
    SUNLinearSolver LS = J ? SUNLinSol_KLU(y, J, ctx) : nullptr;
    if (!J || !LS) throw std::runtime_error("could not create the KLU solver");
    void* mem = IDACreate(ctx);
    if (!mem) throw std::runtime_error("IDACreate failed");
    check(IDAInit(mem, residual, 0.0, y, yp), "IDAInit");
    check(IDASStolerances(mem, rtol, atol), "IDASStolerances");
    check(IDASetUserData(mem, &p), "IDASetUserData");
    check(IDASetId(mem, id), "IDASetId");
    check(IDASetSuppressAlg(mem, SUNTRUE), "IDASetSuppressAlg");
    check(IDASetMaxNumSteps(mem, 100000), "IDASetMaxNumSteps");
    check(IDASetLinearSolver(mem, LS, J), "IDASetLinearSolver");
    check(IDASetJacFn(mem, jacobian), "IDASetJacFn");
    check(IDACalcIC(mem, IDA_YA_YDP_INIT, output_step), "IDACalcIC");
    const long outputs = std::lround(t_end / output_step);
    double tret = 0.0;
    double tip = 0.0;  // uy of the last DOF at t_end, a figure to compare runs by
    for (long k = 1; k <= outputs; ++k) {
      const double tout = k == outputs ? t_end : static_cast<double>(k) * output_step;
      check(IDASolve(mem, tout, &tret, y, yp, IDA_NORMAL), "IDASolve");
    }
    tip = N_VGetArrayPointer(y)[n - 1];
    const double solver_s = seconds_since(solver_start);
    const double solver_cpu_s = cpu_seconds() - solver_cpu_start;

    long steps = 0, res = 0, jacs = 0, nli = 0, ncf = 0, etf = 0, lsres = 0;
    IDAGetNumSteps(mem, &steps);
    IDAGetNumResEvals(mem, &res);
    IDAGetNumJacEvals(mem, &jacs);
    IDAGetNumNonlinSolvIters(mem, &nli);
    IDAGetNumNonlinSolvConvFails(mem, &ncf);
    IDAGetNumErrTestFails(mem, &etf);
    IDAGetNumLinResEvals(mem, &lsres);
    IDAFree(&mem);
    SUNLinSolFree(LS);
    SUNMatDestroy(J);
    N_VDestroy(y);
    N_VDestroy(yp);
    N_VDestroy(id);
    SUNContext_Free(&ctx);

    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf(
        "bare: n=%ld m=%ld unknowns=%ld nnz_jac=%ld steps=%ld residual_evals=%ld "
        "jacobian_evals=%ld "
        "newton_iters=%ld newton_failures=%ld error_test_failures=%ld solver_s=%.6g "
        "solver_cpu_s=%.6g process_s=%.6g process_cpu_s=%.6g peak_rss_mb=%.1f u_last=%.10g\n",
        n, m, size, nnz, steps, res + lsres, jacs, nli, ncf, etf, solver_s, solver_cpu_s,
        seconds_since(process_start), cpu_seconds(), static_cast<double>(usage.ru_maxrss) / 1024.0,
        tip);
  } catch (const std::exception& e) {
    std::cerr << "error: " << dir << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
