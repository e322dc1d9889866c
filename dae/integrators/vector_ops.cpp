// The serial N_Vector's operations, compiled optimized (dae/integrators/vector_ops.hpp).

#include "dae/integrators/vector_ops.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace condyn::sundials {

namespace {

using Index = sunindextype;

Index size(N_Vector v) { return NV_LENGTH_S(v); }
double* data(N_Vector v) { return NV_DATA_S(v); }

/// f(i) for every entry.
template <class F>
void each(Index n, F f) {
  for (Index i = 0; i < n; ++i) f(i);
}

double weighted_square_sum(N_Vector x, N_Vector w, const double* mask) {
  const double* xd = data(x);
  const double* wd = data(w);
  double s = 0.0;
  for (Index i = 0; i < size(x); ++i) {
    const double p = xd[i] * wd[i];
    if (mask == nullptr || mask[i] > 0.0) s += p * p;
  }
  return s;
}

/// sqrt(Σ (x_i w_i)² / divisor) over the unmasked entries. The plain sum first (every step's
/// path, bitwise SUNDIALS' result); when it overflows, the sum again scaled by the largest
/// |x_i w_i|. IDA's first step is 0.5 over the norm of y': a load of 1e150 under weights of
/// 1e10 gave squares beyond the double range, a step of 0, and IDA_ILL_INPUT ('tstop = 0.1 is
/// behind current t = 0').
double weighted_norm(N_Vector x, N_Vector w, const double* mask, double divisor) {
  const double s = weighted_square_sum(x, w, mask);
  if (std::isfinite(s)) return std::sqrt(s / divisor);
  const double* xd = data(x);
  const double* wd = data(w);
  double big = 0.0;
  for (Index i = 0; i < size(x); ++i) {
    if (mask == nullptr || mask[i] > 0.0) big = std::max(big, std::abs(xd[i] * wd[i]));
  }
  if (!std::isfinite(big)) return std::sqrt(s / divisor);  // an infinite or NaN entry
  double t = 0.0;
  for (Index i = 0; i < size(x); ++i) {
    const double q = xd[i] * wd[i] / big;
    if (mask == nullptr || mask[i] > 0.0) t += q * q;
  }
  return big * std::sqrt(t / divisor);
}

void linear_sum(double a, N_Vector x, double b, N_Vector y, N_Vector z) {
  const double* xd = data(x);
  const double* yd = data(y);
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = a * xd[i] + b * yd[i]; });
}

void constant(double c, N_Vector z) {
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = c; });
}

void product(N_Vector x, N_Vector y, N_Vector z) {
  const double* xd = data(x);
  const double* yd = data(y);
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = xd[i] * yd[i]; });
}

void divide(N_Vector x, N_Vector y, N_Vector z) {
  const double* xd = data(x);
  const double* yd = data(y);
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = xd[i] / yd[i]; });
}

void scale(double c, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = c * xd[i]; });
}

void absolute(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = std::abs(xd[i]); });
}

void inverse(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = 1.0 / xd[i]; });
}

void add_constant(N_Vector x, double b, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = xd[i] + b; });
}

double dot(N_Vector x, N_Vector y) {
  const double* xd = data(x);
  const double* yd = data(y);
  double s = 0.0;
  for (Index i = 0; i < size(x); ++i) s += xd[i] * yd[i];
  return s;
}

double max_norm(N_Vector x) {
  const double* xd = data(x);
  double s = 0.0;
  for (Index i = 0; i < size(x); ++i) s = std::max(s, std::abs(xd[i]));
  return s;
}

double wrms_norm(N_Vector x, N_Vector w) {
  return weighted_norm(x, w, nullptr, static_cast<double>(size(x)));
}

double wrms_norm_mask(N_Vector x, N_Vector w, N_Vector id) {
  return weighted_norm(x, w, data(id), static_cast<double>(size(x)));
}

double minimum(N_Vector x) {
  const double* xd = data(x);
  if (size(x) == 0) return 0.0;
  double s = xd[0];
  for (Index i = 1; i < size(x); ++i) s = std::min(s, xd[i]);
  return s;
}

double wl2_norm(N_Vector x, N_Vector w) { return weighted_norm(x, w, nullptr, 1.0); }

double l1_norm(N_Vector x) {
  const double* xd = data(x);
  double s = 0.0;
  for (Index i = 0; i < size(x); ++i) s += std::abs(xd[i]);
  return s;
}

void compare(double c, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  each(size(z), [=](Index i) { zd[i] = std::abs(xd[i]) >= c ? 1.0 : 0.0; });
}

/// z = 1/x where x ≠ 0; false when some x is 0 (SUNDIALS' N_VInvTest).
booleantype inverse_test(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  booleantype all = SUNTRUE;
  for (Index i = 0; i < size(x); ++i) {
    if (xd[i] == 0.0) {
      all = SUNFALSE;
    } else {
      zd[i] = 1.0 / xd[i];
    }
  }
  return all;
}

// Fused operations: one pass over the entries for several vectors.

int linear_combination(int nv, double* c, N_Vector* X, N_Vector z) {
  const Index n = size(z);
  double* zd = data(z);
  std::vector<const double*> xs(static_cast<std::size_t>(nv));
  for (int k = 0; k < nv; ++k) xs[static_cast<std::size_t>(k)] = data(X[k]);
  const double* const* xp = xs.data();
  each(n, [=](Index i) {
    double s = c[0] * xp[0][i];
    for (int k = 1; k < nv; ++k) s += c[k] * xp[k][i];
    zd[i] = s;
  });
  return 0;
}

int scale_add_multi(int nv, double* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  for (int k = 0; k < nv; ++k) linear_sum(a[k], x, 1.0, Y[k], Z[k]);
  return 0;
}

int dot_multi(int nv, N_Vector x, N_Vector* Y, double* dots) {
  for (int k = 0; k < nv; ++k) dots[k] = dot(x, Y[k]);
  return 0;
}

int linear_sum_array(int nv, double a, N_Vector* X, double b, N_Vector* Y, N_Vector* Z) {
  for (int k = 0; k < nv; ++k) linear_sum(a, X[k], b, Y[k], Z[k]);
  return 0;
}

int scale_array(int nv, double* c, N_Vector* X, N_Vector* Z) {
  for (int k = 0; k < nv; ++k) scale(c[k], X[k], Z[k]);
  return 0;
}

int constant_array(int nv, double c, N_Vector* Z) {
  for (int k = 0; k < nv; ++k) constant(c, Z[k]);
  return 0;
}

int wrms_norm_array(int nv, N_Vector* X, N_Vector* W, double* norms) {
  for (int k = 0; k < nv; ++k) norms[k] = wrms_norm(X[k], W[k]);
  return 0;
}

int wrms_norm_mask_array(int nv, N_Vector* X, N_Vector* W, N_Vector id, double* norms) {
  for (int k = 0; k < nv; ++k) norms[k] = wrms_norm_mask(X[k], W[k], id);
  return 0;
}

}  // namespace

N_Vector new_vector(sunindextype n, SUNContext ctx) {
  N_Vector v = N_VNew_Serial(n, ctx);
  if (v != nullptr) use_condyn_vector_ops(v);
  return v;
}

void use_condyn_vector_ops(N_Vector v) {
  if (v == nullptr || N_VGetVectorID(v) != SUNDIALS_NVEC_SERIAL) {
    throw std::invalid_argument("use_condyn_vector_ops: a serial N_Vector is expected");
  }
  N_Vector_Ops o = v->ops;
  o->nvlinearsum = linear_sum;
  o->nvconst = constant;
  o->nvprod = product;
  o->nvdiv = divide;
  o->nvscale = scale;
  o->nvabs = absolute;
  o->nvinv = inverse;
  o->nvaddconst = add_constant;
  o->nvdotprod = dot;
  o->nvmaxnorm = max_norm;
  o->nvwrmsnorm = wrms_norm;
  o->nvwrmsnormmask = wrms_norm_mask;
  o->nvmin = minimum;
  o->nvwl2norm = wl2_norm;
  o->nvl1norm = l1_norm;
  o->nvcompare = compare;
  o->nvinvtest = inverse_test;
  o->nvlinearcombination = linear_combination;
  o->nvscaleaddmulti = scale_add_multi;
  o->nvdotprodmulti = dot_multi;
  o->nvlinearsumvectorarray = linear_sum_array;
  o->nvscalevectorarray = scale_array;
  o->nvconstvectorarray = constant_array;
  o->nvwrmsnormvectorarray = wrms_norm_array;
  o->nvwrmsnormmaskvectorarray = wrms_norm_mask_array;
}

}  // namespace condyn::sundials
