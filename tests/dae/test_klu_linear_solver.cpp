// IDA's sparse Jacobian factored by KLU in 32-bit indices over a fixed pattern
// (dae/integrators/klu_linear_solver.hpp), called as IDA calls it: setup on the integrator's
// matrix, then solves.
#include <doctest/doctest.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "dae/integrators/klu_linear_solver.hpp"
#include "dae/integrators/sundials_raii.hpp"
#include "dae/linsolve/block_jacobian.hpp"
#include "models/core/eigen_decompositions.hpp"

using namespace condyn;

namespace test_klu_linear_solver {

namespace {

/// The values of `dense` on `pattern`, written into the matrix as IDA and the Jacobian callback
/// write them: zeroed, then filled in the pattern.
void fill(const JacobianPattern& pattern, const Eigen::MatrixXd& dense, SUNMatrix a) {
  REQUIRE(SUNMatZero(a) == SUNMAT_SUCCESS);
  JacobianMap J = pattern.map(condyn::sundials::pattern_matrix_values(a));
  for (Eigen::Index k = 0; k < J.nonZeros(); ++k) REQUIRE(J.valuePtr()[k] == 0.0);
  for (int c = 0; c < pattern.size; ++c) {
    for (JacobianMap::InnerIterator it(J, c); it; ++it) it.valueRef() = dense(it.row(), c);
  }
}

}  // namespace

TEST_CASE("make_klu_solver: solves with the values IDA's matrix holds, refactored and restarted") {
  // The pattern of a 4 x 4 matrix: a tridiagonal block and a coupling (0, 3), (3, 0).
  Eigen::SparseMatrix<double> S(4, 4);
  for (int k = 0; k < 4; ++k) {
    S.insert(k, k) = 1.0;
    if (k > 0) S.insert(k, k - 1) = S.insert(k - 1, k) = 1.0;
  }
  S.insert(0, 3) = S.insert(3, 0) = 1.0;
  S.makeCompressed();
  BlockJacobian blocks(4);
  blocks.declare(0, 0, S);
  blocks.finish();
  const JacobianPattern& pattern = blocks.pattern();
  const Eigen::MatrixXd mask = Eigen::MatrixXd(S).cwiseAbs();

  SUNContext raw = nullptr;
  REQUIRE(SUNContext_Create(nullptr, &raw) == 0);
  condyn::sundials::ContextPtr ctx(raw);
  condyn::sundials::MatrixPtr a(condyn::sundials::make_pattern_matrix(pattern, ctx.get()));
  condyn::sundials::SolverPtr solver(condyn::sundials::make_klu_solver(pattern, ctx.get()));
  condyn::sundials::VectorPtr b(N_VNew_Serial(4, ctx.get()));
  condyn::sundials::VectorPtr x(N_VNew_Serial(4, ctx.get()));
  REQUIRE(a);
  CHECK(SUNMatGetID(a.get()) == SUNMATRIX_CUSTOM);
  long lenrw = 0, leniw = 0;
  CHECK(SUNMatSpace(a.get(), &lenrw, &leniw) == SUNMAT_SUCCESS);
  CHECK(lenrw == pattern.nonZeros());  // values only
  CHECK(leniw == 0);
  REQUIRE(solver);
  CHECK(SUNLinSolGetType(solver.get()) == SUNLINEARSOLVER_DIRECT);
  REQUIRE(SUNLinSolInitialize(solver.get()) == SUNLS_SUCCESS);

  const Eigen::Vector4d rhs(1.0, -2.0, 0.5, 3.0);
  const auto solve_and_check = [&](const Eigen::MatrixXd& dense) {
    fill(pattern, dense, a.get());
    REQUIRE(SUNLinSolSetup(solver.get(), a.get()) == SUNLS_SUCCESS);
    condyn::sundials::view(b.get()) = rhs;
    REQUIRE(SUNLinSolSolve(solver.get(), a.get(), x.get(), b.get(), 0.0) == SUNLS_SUCCESS);
    const Eigen::Vector4d expected = dense.fullPivLu().solve(rhs);
    // The three matrices below have condition numbers 2.7, 1.8 and 23 (numpy.linalg.cond): two
    // backward-stable solves differ by a few ε times that, far below 1e-13.
    CHECK((condyn::sundials::view(x.get()) - expected).norm() <= 1e-13 * expected.norm());
    CHECK(condyn::sundials::view(b.get()) == rhs);  // b is left as it was
  };
  // A first matrix (pivoting factorization), another with the same pattern (refactored with the
  // pivots kept), one whose pivots must change (a zero where the first pivot was).
  Eigen::MatrixXd first = mask.cwiseProduct(Eigen::MatrixXd::Constant(4, 4, -1.0));
  first.diagonal() = Eigen::Vector4d(4.0, 5.0, 6.0, 7.0);
  solve_and_check(first);
  Eigen::MatrixXd second = first;
  second.diagonal() *= 3.0;
  second(0, 3) = 2.0;
  solve_and_check(second);
  Eigen::MatrixXd repivot = first;
  repivot(0, 0) = 0.0;
  solve_and_check(repivot);

  // A singular matrix is a recoverable failure (IDA retries with a smaller step); the solver
  // factors again after it, and after a restart of the integrator.
  Eigen::MatrixXd singular = Eigen::MatrixXd::Zero(4, 4);
  singular(0, 0) = singular(1, 1) = singular(2, 2) = 1.0;  // row 3 is zero
  fill(pattern, singular, a.get());
  CHECK(SUNLinSolSetup(solver.get(), a.get()) == SUNLS_PACKAGE_FAIL_REC);
  CHECK(SUNLinSolLastFlag(solver.get()) == SUNLS_PACKAGE_FAIL_REC);
  solve_and_check(second);
  REQUIRE(SUNLinSolInitialize(solver.get()) == SUNLS_SUCCESS);
  solve_and_check(first);

  // Any other matrix, or one made for another pattern, is refused.
  condyn::sundials::MatrixPtr sparse(SUNSparseMatrix(4, 4, pattern.nonZeros(), CSC_MAT, ctx.get()));
  CHECK(condyn::sundials::pattern_matrix_values(sparse.get()) == nullptr);
  CHECK(condyn::sundials::pattern_matrix_values(nullptr) == nullptr);
  CHECK(SUNLinSolSetup(solver.get(), sparse.get()) == SUNLS_ILL_INPUT);
  BlockJacobian diagonal(4);
  diagonal.finish();
  condyn::sundials::MatrixPtr other(
      condyn::sundials::make_pattern_matrix(diagonal.pattern(), ctx.get()));
  CHECK(SUNLinSolSetup(solver.get(), other.get()) == SUNLS_ILL_INPUT);
}

}  // namespace test_klu_linear_solver
