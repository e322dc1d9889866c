// CHOLMOD with its symbolic analysis kept across factorizations
// (models/core/fixed_pattern_cholmod.hpp), loaded with dlopen on first use, after OpenBLAS.

#include "models/core/fixed_pattern_cholmod.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "models/core/load_library.hpp"
#include "models/core/supernodal_solve.hpp"

#ifndef CONDYN_CHOLMOD_SONAME
#error "CONDYN_CHOLMOD_SONAME (CHOLMOD's shared library, e.g. libcholmod.so.3) is set by CMake"
#endif
#ifndef CONDYN_OPENBLAS_SONAME
#error "CONDYN_OPENBLAS_SONAME (OpenBLAS's shared library, e.g. libopenblas.so.0) is set by CMake"
#endif

namespace condyn {

namespace {

/// The entry points of CHOLMOD that condyn calls.
struct CholmodLibrary {
  decltype(&cholmod_start) start = nullptr;
  decltype(&cholmod_finish) finish = nullptr;
  decltype(&cholmod_analyze) analyze = nullptr;
  decltype(&cholmod_factorize) factorize = nullptr;
  decltype(&cholmod_solve2) solve2 = nullptr;
  decltype(&cholmod_free_factor) free_factor = nullptr;
  decltype(&cholmod_free_dense) free_dense = nullptr;
  decltype(&cholmod_rcond) rcond = nullptr;
};

/// CHOLMOD 3's supernodal factorization clears and fills each supernode's block in OpenMP loops
/// of a fixed four threads (its CHOLMOD_OMP_NUM_THREADS), whatever the cores and OMP_NUM_THREADS.
/// On two cores they made a factorization of a 2D mesh's matrix three times slower than the
/// calling thread alone, and spun a second core (docs/benchmarks.md, "The start of a stiff run").
/// Its dense work is OpenBLAS's, on OpenBLAS's own threads. So OpenMP's parallel regions run on
/// the calling thread (max-active-levels 0, a setting of the whole process, which condyn's code
/// does not otherwise use), unless the user set OMP_MAX_ACTIVE_LEVELS or OMP_THREAD_LIMIT.
void serialize_openmp(const LoadedLibrary& cholmod) {
  if (std::getenv("OMP_MAX_ACTIVE_LEVELS") != nullptr || std::getenv("OMP_THREAD_LIMIT") != nullptr)
    return;
  void (*set_max_active_levels)(int) = nullptr;  // libgomp's, when CHOLMOD was built with OpenMP
  if (cholmod.resolve_if_present("omp_set_max_active_levels", set_max_active_levels)) {
    set_max_active_levels(0);
  }
}

/// Loads OpenBLAS, then CHOLMOD, once per process; they stay loaded. A failed load throws
/// LibraryUnavailable and is tried again at the next call.
///
/// Not linked: CHOLMOD brings METIS, LAPACK, BLAS, OpenMP and the gfortran runtime, which a run
/// that never factors with CHOLMOD would load for nothing (models/core/sparse_qr.hpp). OpenBLAS
/// is opened first and global, so that CHOLMOD's BLAS and LAPACK calls (dgemm_, dpotrf_, …) bind
/// to it rather than to the libblas.so.3 and liblapack.so.3 it names, whichever of them the
/// system's alternatives select (the reference BLAS is several times slower on the supernodal
/// blocks).
const CholmodLibrary& cholmod_library() {
  static const CholmodLibrary lib = [] {
    const LoadedLibrary openblas(
        {"OpenBLAS", CONDYN_OPENBLAS_SONAME, "computes the dense blocks of CHOLMOD's factorization",
         "libopenblas0-pthread"},
        LoadedLibrary::Scope::global);
    const LoadedLibrary cholmod(
        {"CHOLMOD", CONDYN_CHOLMOD_SONAME, "factors symmetric positive-definite Newton matrices",
         "libcholmod3"},
        LoadedLibrary::Scope::local);
    CholmodLibrary l;
    cholmod.resolve("cholmod_start", l.start);
    cholmod.resolve("cholmod_finish", l.finish);
    cholmod.resolve("cholmod_analyze", l.analyze);
    cholmod.resolve("cholmod_factorize", l.factorize);
    cholmod.resolve("cholmod_solve2", l.solve2);
    cholmod.resolve("cholmod_free_factor", l.free_factor);
    cholmod.resolve("cholmod_free_dense", l.free_dense);
    cholmod.resolve("cholmod_rcond", l.rcond);
    serialize_openmp(cholmod);
    return l;
  }();
  return lib;
}

/// The orderings tried, in the order they are reported.
constexpr std::pair<int, const char*> kOrderings[] = {
    {CHOLMOD_AMD, "amd"}, {CHOLMOD_METIS, "metis"}, {CHOLMOD_NESDIS, "nesdis"}};

/// One cholmod_common, started and finished with its owner: errors are not printed (condyn
/// reports them), a simplicial factorization is L Lᵀ (so that it, like the supernodal one, finds a
/// matrix that is not positive definite), one ordering per analysis.
struct CholmodCommon {
  const CholmodLibrary& lib = cholmod_library();
  cholmod_common c{};
  CholmodCommon() {
    lib.start(&c);
    c.print = 0;
    c.final_ll = 1;
    c.nmethods = 1;
    c.postorder = 1;
  }
  ~CholmodCommon() { lib.finish(&c); }
  CholmodCommon(const CholmodCommon&) = delete;
  CholmodCommon& operator=(const CholmodCommon&) = delete;
};

/// A view of `matrix`'s lower triangle as CHOLMOD reads it (no copy; CHOLMOD only reads it).
cholmod_sparse lower_view(const Eigen::SparseMatrix<double>& matrix) {
  if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
    throw std::invalid_argument("FixedPatternCholmod: a square compressed matrix is expected");
  }
  cholmod_sparse a{};
  a.nrow = a.ncol = static_cast<std::size_t>(matrix.rows());
  a.nzmax = static_cast<std::size_t>(matrix.nonZeros());
  // CHOLMOD's interface takes non-const pointers; with stype −1 and no conversion asked it
  // reads the arrays only.
  a.p = const_cast<int*>(matrix.outerIndexPtr());
  a.i = const_cast<int*>(matrix.innerIndexPtr());
  a.x = const_cast<double*>(matrix.valuePtr());
  a.stype = -1;
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

/// The bytes of a symbolic factor's numeric values and indices once factored.
double factor_bytes(const cholmod_factor& l, double entries) {
  constexpr double kValue = sizeof(double), kIndex = sizeof(int);
  if (l.is_super != 0) {
    return static_cast<double>(l.xsize) * kValue + static_cast<double>(l.ssize) * kIndex;
  }
  return entries * (kValue + kIndex);
}

/// The symbolic analysis of `a` under `ordering`, or nullptr when the build lacks it or it fails.
cholmod_factor* analyze_with(cholmod_sparse& a, int ordering, CholmodCommon& common) {
  common.c.method[0].ordering = ordering;
  cholmod_factor* l = common.lib.analyze(&a, &common.c);
  if (l != nullptr && common.c.status < CHOLMOD_OK) common.lib.free_factor(&l, &common.c);
  return l;
}

}  // namespace

std::vector<CholmodCandidate> cholmod_candidates(const Eigen::SparseMatrix<double>& matrix) {
  cholmod_sparse a = lower_view(matrix);
  CholmodCommon common;
  std::vector<CholmodCandidate> out;
  for (const auto& [ordering, name] : kOrderings) {
    cholmod_factor* l = analyze_with(a, ordering, common);
    if (l == nullptr) continue;
    const double entries = common.c.lnz;
    out.push_back({name, entries, common.c.fl, factor_bytes(*l, entries)});
    common.lib.free_factor(&l, &common.c);
  }
  if (out.empty())
    throw std::runtime_error("CHOLMOD's symbolic analysis failed under every ordering");
  return out;
}

const CholmodCandidate& least_fill(const std::vector<CholmodCandidate>& candidates) {
  return *std::min_element(candidates.begin(), candidates.end(),
                           [](const CholmodCandidate& x, const CholmodCandidate& y) {
                             return x.factor_entries < y.factor_entries;
                           });
}

struct FixedPatternCholmod::Impl {
  CholmodCommon common;
  cholmod_factor* factor = nullptr;
  /// cholmod_solve2's result and workspace, allocated at the first solve and reused.
  cholmod_dense* x = nullptr;
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;
  std::size_t n = 0;
  /// condyn's two-lane solve on a large supernodal factor (models/core/supernodal_solve.hpp),
  /// made at the first factorization that needs it.
  std::unique_ptr<SupernodalSolve> own_solve;
  bool own_solve_declined = false;  ///< its split left too much to one thread: CHOLMOD solves

  Impl() = default;
  ~Impl() {
    common.lib.free_dense(&x, &common.c);
    common.lib.free_dense(&y, &common.c);
    common.lib.free_dense(&e, &common.c);
    common.lib.free_factor(&factor, &common.c);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
};

FixedPatternCholmod::FixedPatternCholmod(std::string ordering, double own_solve_fewest_entries,
                                         double own_solve_most_shared)
    : impl_(std::make_unique<Impl>()),
      ordering_(std::move(ordering)),
      own_solve_fewest_entries_(own_solve_fewest_entries),
      own_solve_most_shared_(own_solve_most_shared) {
  const auto named = [this](const auto& o) { return ordering_ == o.second; };
  if (!ordering_.empty() && std::none_of(std::begin(kOrderings), std::end(kOrderings), named)) {
    throw std::invalid_argument("FixedPatternCholmod: no ordering '" + ordering_ + "'");
  }
}
FixedPatternCholmod::~FixedPatternCholmod() = default;

int FixedPatternCholmod::solve_lanes() const {
  return impl_->own_solve ? impl_->own_solve->lanes() : 0;
}

bool FixedPatternCholmod::supernodal() const {
  return impl_->factor != nullptr && impl_->factor->is_super != 0;
}

void FixedPatternCholmod::analyze(const Eigen::SparseMatrix<double>& matrix) {
  Impl& k = *impl_;
  cholmod_sparse a = lower_view(matrix);
  double best = 0.0;
  const std::string named = ordering_;
  for (const auto& [ordering, name] : kOrderings) {
    if (!named.empty() && named != name) continue;
    ++analyses_;
    cholmod_factor* l = analyze_with(a, ordering, k.common);
    if (l == nullptr) continue;
    if (k.factor != nullptr && k.common.c.lnz >= best) {
      k.common.lib.free_factor(&l, &k.common.c);
      continue;
    }
    k.common.lib.free_factor(&k.factor, &k.common.c);
    k.factor = l;
    best = k.common.c.lnz;
    ordering_ = name;
  }
  if (k.factor == nullptr) throw std::runtime_error("CHOLMOD's symbolic analysis failed");
  k.n = a.nrow;
}

bool FixedPatternCholmod::factor(const Eigen::SparseMatrix<double>& matrix) {
  Impl& k = *impl_;
  if (k.factor == nullptr) analyze(matrix);
  cholmod_sparse a = lower_view(matrix);
  if (a.nrow != k.n) throw std::invalid_argument("FixedPatternCholmod: the matrix changed size");
  ++factorizations_;
  k.common.lib.factorize(&a, k.factor, &k.common.c);
  if (k.common.c.status == CHOLMOD_NOT_POSDEF) return false;
  if (k.common.c.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  if (k.common.c.status < CHOLMOD_OK) {
    throw std::runtime_error("CHOLMOD factorization failed (status " +
                             std::to_string(k.common.c.status) + ")");
  }
  const cholmod_factor& l = *k.factor;
  if (l.is_super != 0 && static_cast<double>(l.xsize) >= own_solve_fewest_entries_ &&
      !k.own_solve_declined) {
    if (!k.own_solve) {
      auto own = std::make_unique<SupernodalSolve>(
          SupernodalFactorView{static_cast<int>(l.n), static_cast<int>(l.nsuper),
                               static_cast<const int*>(l.super), static_cast<const int*>(l.pi),
                               static_cast<const int*>(l.px), static_cast<const int*>(l.s),
                               static_cast<const double*>(l.x), static_cast<const int*>(l.Perm)});
      k.own_solve_declined = own->shared_share() > own_solve_most_shared_;
      if (!k.own_solve_declined) k.own_solve = std::move(own);
    }
    if (k.own_solve) k.own_solve->set_values(static_cast<const double*>(l.x));
  }
  return true;
}

double FixedPatternCholmod::pivot_ratio() const {
  Impl& k = *impl_;
  if (k.factor == nullptr || k.factor->minor < k.n) {
    throw std::logic_error("FixedPatternCholmod: pivot ratio before a factorization");
  }
  // (min diag(L) / max diag(L))² for L Lᵀ: the LDLᵀ pivots' ratio.
  return k.common.lib.rcond(k.factor, &k.common.c);
}

void FixedPatternCholmod::solve_in_place(Eigen::Ref<Eigen::VectorXd> x) {
  Impl& k = *impl_;
  if (k.factor == nullptr || k.factor->minor < k.n) {
    throw std::logic_error("FixedPatternCholmod: solve before a factorization");
  }
  if (static_cast<std::size_t>(x.size()) != k.n) {
    throw std::invalid_argument("FixedPatternCholmod: right-hand side of wrong size");
  }
  if (k.own_solve) {
    k.own_solve->solve_in_place(x.data());
    return;
  }
  cholmod_dense b{};
  b.nrow = b.nzmax = b.d = k.n;
  b.ncol = 1;
  b.x = x.data();
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  if (k.common.lib.solve2(CHOLMOD_A, k.factor, &b, nullptr, &k.x, nullptr, &k.y, &k.e,
                          &k.common.c) == 0) {
    throw std::runtime_error("CHOLMOD solve failed (status " + std::to_string(k.common.c.status) +
                             ")");
  }
  std::copy_n(static_cast<const double*>(k.x->x), k.n, x.data());
}

}  // namespace condyn
