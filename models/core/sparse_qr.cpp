// SuiteSparseQR through its C interface, loaded with dlopen on first use (see sparse_qr.hpp).
// The calls are those of Eigen's SPQRSupport, which condyn used before: the same ordering,
// threshold and outputs, so the rank decisions are unchanged.

#include "models/core/sparse_qr.hpp"

#include <SuiteSparseQR_C.h>

#include <atomic>
#include <numeric>
#include <stdexcept>
#include <string>

#include "models/core/load_library.hpp"

#ifndef CONDYN_SPQR_SONAME
#error "CONDYN_SPQR_SONAME (SuiteSparseQR's shared library, e.g. libspqr.so.2) is set by CMake"
#endif

namespace condyn {
namespace {

/// The entry points condyn calls, resolved from SuiteSparseQR's shared library (CHOLMOD's come
/// with it, a dependency of that library).
struct Library {
  decltype(&cholmod_l_start) start = nullptr;
  decltype(&cholmod_l_finish) finish = nullptr;
  decltype(&cholmod_l_free) free = nullptr;
  decltype(&cholmod_l_free_sparse) free_sparse = nullptr;
  decltype(&cholmod_l_free_dense) free_dense = nullptr;
  decltype(&SuiteSparseQR_C) qr = nullptr;
  decltype(&SuiteSparseQR_C_factorize) factorize = nullptr;
  decltype(&SuiteSparseQR_C_qmult) qmult = nullptr;
  decltype(&SuiteSparseQR_C_solve) solve = nullptr;
  decltype(&SuiteSparseQR_C_free) free_factor = nullptr;
};

std::atomic<bool> g_loaded{false};

/// Loads the library once per process; it stays loaded. A failed load throws LibraryUnavailable
/// and is tried again at the next call.
const Library& library() {
  static const Library lib = [] {
    // Local: its symbols (and CHOLMOD's) stay out of the global namespace.
    const LoadedLibrary spqr({"SuiteSparseQR", CONDYN_SPQR_SONAME,
                              "checks the rank of large constraint groups", "libspqr2"},
                             LoadedLibrary::Scope::local);
    Library l;
    spqr.resolve("cholmod_l_start", l.start);
    spqr.resolve("cholmod_l_finish", l.finish);
    spqr.resolve("cholmod_l_free", l.free);
    spqr.resolve("cholmod_l_free_sparse", l.free_sparse);
    spqr.resolve("cholmod_l_free_dense", l.free_dense);
    spqr.resolve("SuiteSparseQR_C", l.qr);
    spqr.resolve("SuiteSparseQR_C_factorize", l.factorize);
    spqr.resolve("SuiteSparseQR_C_qmult", l.qmult);
    spqr.resolve("SuiteSparseQR_C_solve", l.solve);
    spqr.resolve("SuiteSparseQR_C_free", l.free_factor);
    g_loaded = true;
    return l;
  }();
  return lib;
}

/// CHOLMOD's workspace and parameters for one computation.
class Common {
 public:
  Common() : lib_(library()) { lib_.start(&cc_); }
  ~Common() { lib_.finish(&cc_); }
  Common(const Common&) = delete;
  Common& operator=(const Common&) = delete;

  [[nodiscard]] const Library& lib() const { return lib_; }
  cholmod_common* get() { return &cc_; }
  [[nodiscard]] std::string status() const {
    return "CHOLMOD status " + std::to_string(cc_.status);
  }

 private:
  const Library& lib_;
  cholmod_common cc_{};
};

/// SuiteSparseQR takes SuiteSparse_long indices.
using LongSparse = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;

/// A CHOLMOD view of a compressed matrix; `a` must outlive it.
cholmod_sparse view(LongSparse& a) {
  a.makeCompressed();
  cholmod_sparse s{};
  s.nrow = static_cast<std::size_t>(a.rows());
  s.ncol = static_cast<std::size_t>(a.cols());
  s.nzmax = static_cast<std::size_t>(a.nonZeros());
  s.p = a.outerIndexPtr();
  s.i = a.innerIndexPtr();
  s.x = a.valuePtr();
  s.stype = 0;
  s.itype = CHOLMOD_LONG;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

/// A CHOLMOD view of a column; `v` must outlive it.
cholmod_dense view(Eigen::VectorXd& v) {
  cholmod_dense d{};
  d.nrow = d.nzmax = d.d = static_cast<std::size_t>(v.size());
  d.ncol = 1;
  d.x = v.data();
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

}  // namespace

bool sparse_qr_loaded() { return g_loaded; }

SparseQrRank sparse_qr_rank(const Eigen::SparseMatrix<double>& a, double tol) {
  Common cc;
  const Library& lib = cc.lib();
  LongSparse a_long(a);
  cholmod_sparse A = view(a_long);
  cholmod_sparse* R = nullptr;
  cholmod_sparse* H = nullptr;
  cholmod_dense* HTau = nullptr;
  SuiteSparse_long* E = nullptr;
  SuiteSparse_long* HPinv = nullptr;
  // [Q, R, E] = qr(A) with Q in Householder form: the outputs Eigen's SPQR::compute asks for.
  const SuiteSparse_long rank =
      lib.qr(SPQR_ORDERING_DEFAULT, tol, static_cast<SuiteSparse_long>(a.cols()), 0, &A, nullptr,
             nullptr, nullptr, nullptr, &R, &E, &H, &HPinv, &HTau, cc.get());
  SparseQrRank result;
  result.rank = static_cast<int>(rank);
  result.order.resize(static_cast<std::size_t>(a.cols()));
  if (E) {
    for (std::size_t k = 0; k < result.order.size(); ++k) result.order[k] = static_cast<int>(E[k]);
  } else {  // the identity
    std::iota(result.order.begin(), result.order.end(), 0);
  }
  lib.free_sparse(&R, cc.get());
  lib.free_sparse(&H, cc.get());
  lib.free_dense(&HTau, cc.get());
  lib.free(static_cast<std::size_t>(a.cols()), sizeof(SuiteSparse_long), E, cc.get());
  lib.free(static_cast<std::size_t>(a.rows()), sizeof(SuiteSparse_long), HPinv, cc.get());
  if (rank < 0) throw std::runtime_error("SuiteSparseQR failed on A^T (" + cc.status() + ")");
  return result;
}

struct SparseLeastSquares::Factor {
  Common cc;
  LongSparse basis;
  SuiteSparseQR_C_factorization* qr = nullptr;
};

SparseLeastSquares::SparseLeastSquares(const Eigen::SparseMatrix<double>& basis, double tol)
    : factor_(std::make_unique<Factor>()) {
  Factor& f = *factor_;
  f.basis = basis;
  cholmod_sparse A = view(f.basis);
  f.qr = f.cc.lib().factorize(SPQR_ORDERING_DEFAULT, tol, &A, f.cc.get());
  if (!f.qr) throw std::runtime_error("SuiteSparseQR failed on a basis (" + f.cc.status() + ")");
}

SparseLeastSquares::~SparseLeastSquares() {
  factor_->cc.lib().free_factor(&factor_->qr, factor_->cc.get());
}

Eigen::VectorXd SparseLeastSquares::solve(const Eigen::VectorXd& b) const {
  Factor& f = *factor_;
  const Library& lib = f.cc.lib();
  Eigen::VectorXd rhs = b;
  cholmod_dense B = view(rhs);
  // y = E (R \ (Q' b)), as Eigen's SPQR::solve.
  cholmod_dense* qtb = lib.qmult(SPQR_QTX, f.qr, &B, f.cc.get());
  cholmod_dense* x = qtb ? lib.solve(SPQR_RETX_EQUALS_B, f.qr, qtb, f.cc.get()) : nullptr;
  lib.free_dense(&qtb, f.cc.get());
  if (!x)
    throw std::runtime_error("SuiteSparseQR failed on a least-squares solve (" + f.cc.status() +
                             ")");
  Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x),
                                                        static_cast<Eigen::Index>(x->nrow));
  lib.free_dense(&x, f.cc.get());
  return y;
}

}  // namespace condyn
