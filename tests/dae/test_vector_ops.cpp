// condyn's serial N_Vector operations (dae/integrators/vector_ops.hpp) against SUNDIALS' own serial
// ones on the same data, fused operations included.

#include <doctest/doctest.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "dae/integrators/vector_ops.hpp"

namespace test_vector_ops {

namespace {

struct Vectors {
  SUNContext ctx = nullptr;
  std::vector<N_Vector> plain, fast;  ///< SUNDIALS' operations, condyn's; equal contents
  Vectors(long n, int count) {
    SUNContext_Create(nullptr, &ctx);
    for (int k = 0; k < count; ++k) {
      plain.push_back(N_VNew_Serial(n, ctx));
      fast.push_back(condyn::sundials::new_vector(n, ctx));  // with condyn's operations
      for (long i = 0; i < n; ++i) {
        const double x = std::sin(0.37 * static_cast<double>(i) + 1.1 * k) + 0.1 * k;
        NV_Ith_S(plain.back(), i) = x;
        NV_Ith_S(fast.back(), i) = x;
      }
    }
  }
  ~Vectors() {
    for (N_Vector v : plain) N_VDestroy(v);
    for (N_Vector v : fast) N_VDestroy(v);
    SUNContext_Free(&ctx);
  }
  Vectors(const Vectors&) = delete;
  Vectors& operator=(const Vectors&) = delete;
};

Eigen::Map<Eigen::VectorXd> values(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

/// The same up to a few roundoffs (SUNDIALS orders some sums differently: (a x + a y) against
/// a (x + y), block sums against one running sum).
void check_same(N_Vector plain, N_Vector fast) {
  const double scale = std::max(1.0, values(plain).cwiseAbs().maxCoeff());
  CHECK((values(plain) - values(fast)).cwiseAbs().maxCoeff() <= 4e-16 * scale);
}

void check_same(double plain, double fast) {
  CHECK(std::abs(plain - fast) <= 1e-13 * std::max(1.0, std::abs(plain)));
}

}  // namespace

TEST_CASE("condyn's N_Vector operations give SUNDIALS' results") {
  for (const long n : {1L, 7L, 100003L}) {
    CAPTURE(n);
    Vectors v(n, 6);
    auto& p = v.plain;
    auto& f = v.fast;
    CHECK(N_VGetVectorID(f[0]) == SUNDIALS_NVEC_SERIAL);
    // Clones keep the operations (IDA clones its work vectors from y).
    N_Vector clone = N_VClone(f[0]);
    const bool same_as_fast = clone->ops->nvlinearsum == f[0]->ops->nvlinearsum;
    const bool same_as_plain = clone->ops->nvlinearsum == p[0]->ops->nvlinearsum;
    CHECK(same_as_fast);
    CHECK_FALSE(same_as_plain);
    N_VDestroy(clone);

    for (const auto& [a, b] :
         {std::pair{1.0, 1.0}, {1.0, -1.0}, {-1.0, 2.5}, {0.3, 0.3}, {2.0, 0.7}}) {
      N_VLinearSum(a, p[0], b, p[1], p[5]);
      N_VLinearSum(a, f[0], b, f[1], f[5]);
      check_same(p[5], f[5]);
    }
    N_VLinearSum(2.0, p[0], 1.0, p[5], p[5]);  // z aliasing y
    N_VLinearSum(2.0, f[0], 1.0, f[5], f[5]);
    check_same(p[5], f[5]);
    N_VProd(p[0], p[1], p[5]);
    N_VProd(f[0], f[1], f[5]);
    check_same(p[5], f[5]);
    N_VDiv(p[0], p[2], p[5]);
    N_VDiv(f[0], f[2], f[5]);
    check_same(p[5], f[5]);
    N_VScale(-3.0, p[1], p[5]);
    N_VScale(-3.0, f[1], f[5]);
    check_same(p[5], f[5]);
    N_VAbs(p[0], p[5]);
    N_VAbs(f[0], f[5]);
    check_same(p[5], f[5]);
    N_VInv(p[2], p[5]);
    N_VInv(f[2], f[5]);
    check_same(p[5], f[5]);
    N_VAddConst(p[0], 0.25, p[5]);
    N_VAddConst(f[0], 0.25, f[5]);
    check_same(p[5], f[5]);
    N_VCompare(0.5, p[0], p[5]);
    N_VCompare(0.5, f[0], f[5]);
    check_same(p[5], f[5]);
    N_VConst(1.5, p[5]);
    N_VConst(1.5, f[5]);
    check_same(p[5], f[5]);

    check_same(N_VDotProd(p[0], p[1]), N_VDotProd(f[0], f[1]));
    check_same(N_VMaxNorm(p[0]), N_VMaxNorm(f[0]));
    check_same(N_VWrmsNorm(p[0], p[1]), N_VWrmsNorm(f[0], f[1]));
    check_same(N_VWrmsNormMask(p[0], p[1], p[2]), N_VWrmsNormMask(f[0], f[1], f[2]));
    check_same(N_VMin(p[3]), N_VMin(f[3]));
    check_same(N_VWL2Norm(p[0], p[1]), N_VWL2Norm(f[0], f[1]));
    check_same(N_VL1Norm(p[0]), N_VL1Norm(f[0]));

    // Inverse test: true without zeros; with a zero, false and the other entries inverted.
    CHECK(N_VInvTest(f[2], f[5]) == N_VInvTest(p[2], p[5]));
    check_same(p[5], f[5]);
    NV_Ith_S(p[4], 0) = 0.0;
    NV_Ith_S(f[4], 0) = 0.0;
    N_VConst(7.0, p[5]);
    N_VConst(7.0, f[5]);
    CHECK(N_VInvTest(f[4], f[5]) == SUNFALSE);
    CHECK(N_VInvTest(p[4], p[5]) == SUNFALSE);
    check_same(p[5], f[5]);

    // Fused operations (SUNDIALS' serial ones, enabled, are the reference).
    for (N_Vector x : p) N_VEnableFusedOps_Serial(x, SUNTRUE);
    double c[4] = {1.0, -0.5, 2.0, 0.125};
    N_VLinearCombination(4, c, p.data(), p[5]);
    N_VLinearCombination(4, c, f.data(), f[5]);
    check_same(p[5], f[5]);
    N_Vector pz[2] = {p[5], p[0]};
    N_Vector fz[2] = {f[5], f[0]};
    N_VLinearCombination(2, c, pz, p[5]);  // z is X[0]
    N_VLinearCombination(2, c, fz, f[5]);
    check_same(p[5], f[5]);
    N_Vector pY[2] = {p[1], p[2]}, fY[2] = {f[1], f[2]};
    N_Vector pZ[2] = {p[4], p[5]}, fZ[2] = {f[4], f[5]};
    N_VScaleAddMulti(2, c, p[0], pY, pZ);
    N_VScaleAddMulti(2, c, f[0], fY, fZ);
    check_same(p[4], f[4]);
    check_same(p[5], f[5]);
    N_VLinearSumVectorArray(2, 0.5, pY, -2.0, pZ, pZ);
    N_VLinearSumVectorArray(2, 0.5, fY, -2.0, fZ, fZ);
    check_same(p[4], f[4]);
    check_same(p[5], f[5]);
    N_VScaleVectorArray(2, c, pY, pZ);
    N_VScaleVectorArray(2, c, fY, fZ);
    check_same(p[4], f[4]);
    check_same(p[5], f[5]);
    double pd[2], fd[2];
    N_VDotProdMulti(2, p[0], pY, pd);
    N_VDotProdMulti(2, f[0], fY, fd);
    check_same(pd[0], fd[0]);
    check_same(pd[1], fd[1]);
    N_VWrmsNormVectorArray(2, pY, pZ, pd);
    N_VWrmsNormVectorArray(2, fY, fZ, fd);
    check_same(pd[1], fd[1]);
    N_VWrmsNormMaskVectorArray(2, pY, pZ, p[3], pd);
    N_VWrmsNormMaskVectorArray(2, fY, fZ, f[3], fd);
    check_same(pd[0], fd[0]);
    N_VConstVectorArray(2, -1.0, pZ);
    N_VConstVectorArray(2, -1.0, fZ);
    check_same(p[5], f[5]);
  }
}

TEST_CASE("weighted norms do not overflow where their squares would") {
  // |x w| = 1e160 squares to inf: SUNDIALS' norm is inf, and IDA's first step (0.5 over the
  // norm of y') was 0, refused as 'tstop is behind current t' for a load of 1e150.
  const Vectors v(4, 3);
  N_Vector x = v.fast[0], w = v.fast[1], id = v.fast[2];
  const double entries[4] = {1e160, -2e160, 0.0, 3e159};
  for (long i = 0; i < 4; ++i) {
    NV_Ith_S(x, i) = entries[i];
    NV_Ith_S(w, i) = 1.0;
    NV_Ith_S(id, i) = i == 1 ? 0.0 : 1.0;  // the largest entry masked out
  }
  const double sum = 1.0 + 4.0 + 0.0 + 0.09;  // of (x / 1e160)², exact enough at 1e-15
  CHECK(N_VWrmsNorm(x, w) == doctest::Approx(1e160 * std::sqrt(sum / 4.0)).epsilon(1e-15));
  CHECK(N_VWL2Norm(x, w) == doctest::Approx(1e160 * std::sqrt(sum)).epsilon(1e-15));
  CHECK(N_VWrmsNormMask(x, w, id) ==
        doctest::Approx(1e160 * std::sqrt((sum - 4.0) / 4.0)).epsilon(1e-15));
  NV_Ith_S(x, 0) = INFINITY;  // an infinite entry stays infinite
  CHECK(std::isinf(N_VWrmsNorm(x, w)));
}

}  // namespace test_vector_ops
