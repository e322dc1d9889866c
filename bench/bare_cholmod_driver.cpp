// The floor for CHOLMOD (issue 47, items 2 and 3): a bare SUNDIALS IDA + CHOLMOD driver, no
// condyn code, on the matrices bench/mesh_lattice.py (or bench/lattice.py) writes. CHOLMOD factors
// symmetric positive-definite matrices only, so the constraints are penalty springs, as condyn's
// `scheme = "penalty"` makes them on a linear model: row i of A (a_i) adds w a_iᵀ a_i / |a_i|²
// to the stiffness, K_w = K + w Aᵀ D A with D = diag(1 / |a_i|²). The system
//   u' = v,   M v' = s(t) f − K_w u,
// y = [u; v], s(t) the unit step, u(0) = v(0) = 0, v'(0) = M⁻¹ f by IDACalcIC, scalar tolerances.
// Its Newton matrix [cj I, −I; K_w, cj M] is condensed to u: (K_w + cj² M) du = r₂ + cj M r₁,
// dv = cj du − r₁, factored by CHOLMOD (supernodal, the least-fill ordering of AMD, METIS and
// nested dissection chosen at the first analysis, the analysis kept) inside a matrix-embedded
// SUNLinearSolver, again at each change of IDA's cj (or beyond --max-cj-change; between, the
// solutions of the stale factor are scaled as IDA scales a matrix-based solver's).
//
//   condyn_bare_cholmod_driver DIR --weight W [--t-end T] [--output-step H] [--rtol R] [--atol A]
//                              [--max-cj-change C]
// prints one line of key=value figures as condyn_bare_driver does (jacobian_evals: the
// factorizations). CHOLMOD's OpenMP loops run on
// the calling thread (max-active-levels 0), as condyn runs them: with CHOLMOD's own four threads
// its factorizations took three times as long on two cores (docs/benchmarks.md).
#include <cholmod.h>
#include <dlfcn.h>
#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#include <sys/resource.h>

#include <algorithm>
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
  Csc M, Kw;
  std::vector<double> f;
  long n = 0;
  void* ida = nullptr;
  // The condensed matrix K_w + cj² M as CHOLMOD reads it: its lower triangle, the positions of
  // K_w's and M's entries in it, and the factor.
  cholmod_common common{};
  cholmod_sparse* lower = nullptr;
  std::vector<long> k_at, m_at;
  std::vector<double> k_val, m_val;
  cholmod_factor* factor = nullptr;
  cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr, *b = nullptr;
  double cj_setup = 0.0;
  /// Factors again when IDA's cj has moved more than this relative change from the factored
  /// one's (0: at every change, as condyn's penalty scheme does; condyn reuses a factor only under
  /// elimination). IDA does not call a matrix-embedded solver's setup without a matrix or a
  /// preconditioner, so the solve decides.
  double max_cj_change = 0.0;
  long factorizations = 0;
};

/// C = A + B of two CSC matrices of the same size (rows sorted, no duplicates).
Csc add(const Csc& a, const Csc& b) {
  Csc c;
  c.rows = a.rows;
  c.cols = a.cols;
  c.ptr.push_back(0);
  for (long j = 0; j < a.cols; ++j) {
    long p = a.ptr[j], q = b.ptr[j];
    while (p < a.ptr[j + 1] || q < b.ptr[j + 1]) {
      const long ra = p < a.ptr[j + 1] ? a.idx[p] : a.rows;
      const long rb = q < b.ptr[j + 1] ? b.idx[q] : b.rows;
      const long r = std::min(ra, rb);
      double v = 0.0;
      if (ra == r) v += a.val[p++];
      if (rb == r) v += b.val[q++];
      c.idx.push_back(r);
      c.val.push_back(v);
    }
    c.ptr.push_back(static_cast<long>(c.idx.size()));
  }
  return c;
}

/// w Aᵀ D A, D = diag(1 / |a_i|²): each row's penalty spring along its unit normal.
Csc penalty_stiffness(const Csc& A, double w) {
  const Csc At = transpose(A);  // column i of At is row a_i
  std::vector<double> norm2(static_cast<std::size_t>(A.rows), 0.0);
  for (long k = 0; k < static_cast<long>(A.idx.size()); ++k)
    norm2[static_cast<std::size_t>(A.idx[k])] += A.val[k] * A.val[k];
  // Σ_i (w / |a_i|²) a_iᵀ a_i, built column by column with a dense accumulator per column.
  Csc out;
  out.rows = out.cols = A.cols;
  out.ptr.assign(1, 0);
  std::vector<double> acc(static_cast<std::size_t>(A.cols), 0.0);
  std::vector<char> used(static_cast<std::size_t>(A.cols), 0);
  std::vector<long> rows;
  for (long j = 0; j < A.cols; ++j) {
    rows.clear();
    for (long k = A.ptr[j]; k < A.ptr[j + 1]; ++k) {  // rows i of A with a_ij != 0
      const long i = A.idx[k];
      const double s = w * A.val[k] / norm2[static_cast<std::size_t>(i)];
      for (long q = At.ptr[i]; q < At.ptr[i + 1]; ++q) {
        const auto r = static_cast<std::size_t>(At.idx[q]);
        if (!used[r]) {
          used[r] = 1;
          rows.push_back(At.idx[q]);
        }
        acc[r] += s * At.val[q];
      }
    }
    std::sort(rows.begin(), rows.end());
    for (long r : rows) {
      out.idx.push_back(r);
      out.val.push_back(acc[static_cast<std::size_t>(r)]);
      acc[static_cast<std::size_t>(r)] = 0.0;
      used[static_cast<std::size_t>(r)] = 0;
    }
    out.ptr.push_back(static_cast<long>(out.idx.size()));
  }
  return out;
}

/// The lower triangle of the pattern of K_w + M, with where each entry of K_w and M goes.
void build_condensed(Problem& p) {
  const Csc pattern = add(p.Kw, p.M);
  long nnz = 0;
  for (long j = 0; j < pattern.cols; ++j)
    for (long k = pattern.ptr[j]; k < pattern.ptr[j + 1]; ++k) nnz += pattern.idx[k] >= j;
  p.lower =
      cholmod_allocate_sparse(static_cast<std::size_t>(p.n), static_cast<std::size_t>(p.n),
                              static_cast<std::size_t>(nnz), 1, 1, -1, CHOLMOD_REAL, &p.common);
  if (p.lower == nullptr) throw std::runtime_error("cholmod_allocate_sparse failed");
  auto* ptr = static_cast<int*>(p.lower->p);
  auto* idx = static_cast<int*>(p.lower->i);
  long at = 0;
  for (long j = 0; j < p.n; ++j) {
    ptr[j] = static_cast<int>(at);
    for (long k = pattern.ptr[j]; k < pattern.ptr[j + 1]; ++k)
      if (pattern.idx[k] >= j) idx[at++] = static_cast<int>(pattern.idx[k]);
  }
  ptr[p.n] = static_cast<int>(at);
  // Each lower entry of K_w and M: its place in the lower pattern (rows sorted in both).
  const auto place = [&](const Csc& a, std::vector<long>& where, std::vector<double>& val) {
    for (long j = 0; j < p.n; ++j) {
      long q = ptr[j];
      for (long k = a.ptr[j]; k < a.ptr[j + 1]; ++k) {
        if (a.idx[k] < j) continue;
        while (idx[q] != a.idx[k]) ++q;
        where.push_back(q);
        val.push_back(a.val[k]);
      }
    }
  };
  place(p.Kw, p.k_at, p.k_val);
  place(p.M, p.m_at, p.m_val);
}

/// Factors K_w + cj² M; false when CHOLMOD fails (not positive definite, out of memory).
bool factor(Problem& p, double cj) {
  auto* x = static_cast<double*>(p.lower->x);
  std::fill(x, x + static_cast<long>(p.lower->nzmax), 0.0);
  for (std::size_t k = 0; k < p.k_at.size(); ++k) x[p.k_at[k]] += p.k_val[k];
  for (std::size_t k = 0; k < p.m_at.size(); ++k) x[p.m_at[k]] += cj * cj * p.m_val[k];
  if (p.factor == nullptr) {  // the first time: analyze under each ordering, keep the least fill
    p.common.nmethods = 3;
    p.common.method[0].ordering = CHOLMOD_AMD;
    p.common.method[1].ordering = CHOLMOD_METIS;
    p.common.method[2].ordering = CHOLMOD_NESDIS;
    p.factor = cholmod_analyze(p.lower, &p.common);
    if (p.factor == nullptr) return false;
  }
  ++p.factorizations;
  return cholmod_factorize(p.lower, p.factor, &p.common) != 0 && p.common.status == CHOLMOD_OK;
}

int residual(double t, N_Vector yy, N_Vector yp, N_Vector rr, void* user) {
  const auto& p = *static_cast<Problem*>(user);
  bare::second_order_residual(p.M, p.Kw, p.f, t, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp),
                              N_VGetArrayPointer(rr));
  return 0;
}

Problem& problem_of(SUNLinearSolver s) { return *static_cast<Problem*>(s->content); }

SUNLinearSolver_Type ls_type(SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }

// x = J⁻¹ b with J at the factored cj: du from the condensed system, then dv = cj du − r₁.
int ls_solve(SUNLinearSolver s, SUNMatrix, N_Vector xv, N_Vector bv, double) {
  Problem& p = problem_of(s);
  double current = 0.0;
  if (IDAGetCurrentCj(p.ida, &current) != IDA_SUCCESS) return SUNLS_MEM_NULL;
  if (p.factor == nullptr || std::abs(current / p.cj_setup - 1.0) > p.max_cj_change) {
    if (!factor(p, current)) return SUNLS_PACKAGE_FAIL_REC;
    p.cj_setup = current;
  }
  const long n = p.n;
  const double cj = p.cj_setup;
  const double* b = N_VGetArrayPointer(bv);
  double* rhs = static_cast<double*>(p.b->x);
  for (long i = 0; i < n; ++i) rhs[i] = b[n + i];
  gaxpy(p.M, b, cj, rhs);  // r₂ + cj M r₁
  if (cholmod_solve2(CHOLMOD_A, p.factor, p.b, nullptr, &p.x, nullptr, &p.y, &p.e, &p.common) == 0)
    return SUNLS_PACKAGE_FAIL_UNREC;
  const double* du = static_cast<const double*>(p.x->x);
  double* x = N_VGetArrayPointer(xv);
  // A stale factor's solution scaled as IDA scales a matrix-based solver's: 2 / (1 + cj / cj₀).
  const double scale = current == cj ? 1.0 : 2.0 / (1.0 + current / cj);
  for (long i = 0; i < n; ++i) {
    const double r1 = b[i];
    x[i] = scale * du[i];
    x[n + i] = scale * (cj * du[i] - r1);
  }
  return SUNLS_SUCCESS;
}

int ls_free(SUNLinearSolver s) {
  s->content = nullptr;
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

}  // namespace

int main(int argc, char** argv) {
  const auto process_start = Clock::now();
  if (argc < 2) {
    std::cerr << "usage: condyn_bare_cholmod_driver DIR --weight W [--t-end T] [--output-step H] "
                 "[--rtol R] [--atol A] [--max-cj-change C]\n";
    return 2;
  }
  const std::string dir = argv[1];
  double t_end = 1.0, output_step = 0.01, rtol = 1e-6, atol = 1e-8, weight = 0.0,
         max_cj_change = 0.0;
  if (!bare::parse_number_flags(argc, argv, 2,
                                {{"--t-end", {&t_end}},
                                 {"--output-step", {&output_step}},
                                 {"--rtol", {&rtol}},
                                 {"--atol", {&atol}},
                                 {"--weight", {&weight}},
                                 {"--max-cj-change", {&max_cj_change, true}}}))
    return 2;
  if (!(weight > 0.0)) {
    std::cerr << "error: --weight W (the penalty weight, as condyn's [solve] penalty) is needed\n";
    return 2;
  }
  try {
    Problem p;
    bare::MatrixFiles files = bare::read_matrix_files(dir);
    p.M = std::move(files.M);
    p.f = std::move(files.f);
    p.n = p.M.rows;
    const Csc& K = files.K;
    const Csc& A = files.A;
    p.Kw = add(K, penalty_stiffness(A, weight));
    p.max_cj_change = max_cj_change;
    const long n = p.n, size = 2 * n;

    const auto solver_start = Clock::now();
    const double solver_cpu_start = cpu_seconds();
    // libgomp is in the process as CHOLMOD's dependency.
    if (auto* set_levels =
            reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels")))
      set_levels(0);
    cholmod_start(&p.common);
    p.common.print = 0;
    build_condensed(p);
    p.b = cholmod_zeros(static_cast<std::size_t>(n), 1, CHOLMOD_REAL, &p.common);
    SUNContext ctx = nullptr;
    check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
    N_Vector y = N_VNew_Serial(size, ctx), yp = N_VNew_Serial(size, ctx);
    if (!y || !yp) throw std::runtime_error("N_VNew_Serial failed");
    N_VConst(0.0, y);
    N_VConst(0.0, yp);
    SUNLinearSolver LS = SUNLinSolNewEmpty(ctx);
    if (!LS) throw std::runtime_error("SUNLinSolNewEmpty failed");
    LS->content = &p;
    LS->ops->gettype = ls_type;
    LS->ops->solve = ls_solve;
    LS->ops->free = ls_free;
    // y(0) = 0; y'(0) = [0; M⁻¹ f], consistent: M factored by CHOLMOD once.
    {
      cholmod_sparse mv{};  // a view of M, its indices as CHOLMOD's int
      std::vector<int> mp(p.M.ptr.begin(), p.M.ptr.end()), mi(p.M.idx.begin(), p.M.idx.end());
      mv.nrow = mv.ncol = static_cast<std::size_t>(n);
      mv.nzmax = p.M.idx.size();
      mv.p = mp.data();
      mv.i = mi.data();
      mv.x = p.M.val.data();
      mv.stype = 1;  // its upper triangle (M is symmetric)
      mv.itype = CHOLMOD_INT;
      mv.xtype = CHOLMOD_REAL;
      mv.dtype = CHOLMOD_DOUBLE;
      mv.sorted = 1;
      mv.packed = 1;
      cholmod_factor* lm = cholmod_analyze(&mv, &p.common);
      if (lm == nullptr || !cholmod_factorize(&mv, lm, &p.common) || p.common.status != CHOLMOD_OK)
        throw std::runtime_error("M is not positive definite");
      std::copy(p.f.begin(), p.f.end(), static_cast<double*>(p.b->x));
      cholmod_dense* a0 = cholmod_solve(CHOLMOD_A, lm, p.b, &p.common);
      if (a0 == nullptr) throw std::runtime_error("cholmod_solve failed on M");
      std::copy_n(static_cast<const double*>(a0->x), n, N_VGetArrayPointer(yp) + n);
      cholmod_free_dense(&a0, &p.common);
      cholmod_free_factor(&lm, &p.common);
    }
    p.ida = IDACreate(ctx);
    if (!p.ida) throw std::runtime_error("IDACreate failed");
    check(IDAInit(p.ida, residual, 0.0, y, yp), "IDAInit");
    check(IDASStolerances(p.ida, rtol, atol), "IDASStolerances");
    check(IDASetUserData(p.ida, &p), "IDASetUserData");
    check(IDASetMaxNumSteps(p.ida, 100000), "IDASetMaxNumSteps");
    check(IDASetLinearSolver(p.ida, LS, nullptr), "IDASetLinearSolver");
    const long outputs = std::lround(t_end / output_step);
    double tret = 0.0;
    for (long k = 1; k <= outputs; ++k) {
      const double tout = k == outputs ? t_end : static_cast<double>(k) * output_step;
      check(IDASolve(p.ida, tout, &tret, y, yp, IDA_NORMAL), "IDASolve");
    }
    const double tip = N_VGetArrayPointer(y)[n - 1];
    const double solver_s = seconds_since(solver_start);
    const double solver_cpu_s = cpu_seconds() - solver_cpu_start;

    long steps = 0, res = 0, nli = 0, ncf = 0, etf = 0;
    IDAGetNumSteps(p.ida, &steps);
    IDAGetNumResEvals(p.ida, &res);
    IDAGetNumNonlinSolvIters(p.ida, &nli);
    IDAGetNumNonlinSolvConvFails(p.ida, &ncf);
    IDAGetNumErrTestFails(p.ida, &etf);
    const double factor_entries = p.factor->is_super ? static_cast<double>(p.factor->xsize)
                                                     : static_cast<double>(p.factor->nzmax);
    const int ordering = p.factor->ordering;
    IDAFree(&p.ida);
    SUNLinSolFree(LS);
    N_VDestroy(y);
    N_VDestroy(yp);
    SUNContext_Free(&ctx);
    cholmod_free_factor(&p.factor, &p.common);
    cholmod_free_sparse(&p.lower, &p.common);
    cholmod_free_dense(&p.b, &p.common);
    cholmod_free_dense(&p.x, &p.common);
    cholmod_free_dense(&p.y, &p.common);
    cholmod_free_dense(&p.e, &p.common);
    cholmod_finish(&p.common);

    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf(
        "bare_cholmod: n=%ld unknowns=%ld ordering=%s factor_entries=%.4g steps=%ld "
        "residual_evals=%ld jacobian_evals=%ld newton_iters=%ld newton_failures=%ld "
        "error_test_failures=%ld solver_s=%.6g solver_cpu_s=%.6g process_s=%.6g "
        "process_cpu_s=%.6g peak_rss_mb=%.1f u_last=%.10g\n",
        n, size,
        ordering == CHOLMOD_AMD      ? "amd"
        : ordering == CHOLMOD_METIS  ? "metis"
        : ordering == CHOLMOD_NESDIS ? "nesdis"
                                     : "other",
        factor_entries, steps, res, p.factorizations, nli, ncf, etf, solver_s, solver_cpu_s,
        seconds_since(process_start), cpu_seconds(), static_cast<double>(usage.ru_maxrss) / 1024.0,
        tip);
  } catch (const std::exception& e) {
    std::cerr << "error: " << dir << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
