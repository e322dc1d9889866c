// [initial] static = true: the sparse saddle-point solve of a linear model's static equilibrium
// (models/assembly/static_equilibrium.hpp).

#include "models/assembly/static_equilibrium.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "models/core/eigen_decompositions.hpp"

namespace condyn {

namespace {

// A condition estimate above this is a singular matrix to roundoff: an exact mechanism leaves a
// pivot of a few ulps of ‖K‖, an estimate near 1/eps ≈ 4.5e15; a sound model that far out has
// lost all but three digits of its equilibrium anyway.
constexpr double kSingularCondition = 1e13;
// The DOFs named in a refusal: those whose probe entry is within this factor of the largest.
constexpr double kModeShare = 0.5;
constexpr std::size_t kMaxNamedDofs = 8;

double norm1(const Eigen::SparseMatrix<double>& S) {
  double out = 0.0;
  for (Eigen::Index k = 0; k < S.outerSize(); ++k) {
    double col = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(S, k); it; ++it) col += std::abs(it.value());
    out = std::max(out, col);
  }
  return out;
}

/// DOFs with no nonzero in K's or A's column: nothing holds them.
std::vector<int> untouched_dofs(const Eigen::SparseMatrix<double>& K,
                                const Eigen::SparseMatrix<double>& A) {
  const auto n = static_cast<std::size_t>(K.cols());
  std::vector<bool> held(n, false);
  for (Eigen::Index k = 0; k < K.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, k); it; ++it) {
      if (it.value() != 0.0) held[static_cast<std::size_t>(it.col())] = true;
    }
  }
  for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      if (it.value() != 0.0) held[static_cast<std::size_t>(it.col())] = true;
    }
  }
  std::vector<int> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (!held[i]) out.push_back(static_cast<int>(i));
  }
  return out;
}

/// The DOFs a (near-)null vector moves most, largest first.
std::vector<int> mode_dofs(const Eigen::VectorXd& x_u) {
  std::vector<int> out;
  const double top = x_u.lpNorm<Eigen::Infinity>();
  if (!(top > 0.0)) return out;
  for (Eigen::Index i = 0; i < x_u.size(); ++i) {
    if (std::abs(x_u[i]) >= kModeShare * top) out.push_back(static_cast<int>(i));
  }
  std::sort(out.begin(), out.end(),
            [&](int a, int b) { return std::abs(x_u[a]) > std::abs(x_u[b]); });
  if (out.size() > kMaxNamedDofs) out.resize(kMaxNamedDofs);
  return out;
}

}  // namespace

StaticEquilibrium solve_static_equilibrium(const Eigen::SparseMatrix<double>& K,
                                           const Eigen::SparseMatrix<double>& A,
                                           const Eigen::VectorXd& f, const Eigen::VectorXd& g) {
  const Eigen::Index n = K.rows(), m = A.rows();
  if (K.cols() != n || f.size() != n || g.size() != m || (m > 0 && A.cols() != n)) {
    throw std::invalid_argument("solve_static_equilibrium: the sizes of K, A, f and g disagree");
  }
  if (const auto free = untouched_dofs(K, A); !free.empty()) {
    throw NoStaticEquilibrium("no stiffness or constraint holds some DOFs", free);
  }
  // Row i of A scaled by D_ii = ‖K‖_max / max_j |a_ij|: the multiplier block's pivots then have
  // K's size (λ = D μ undoes it).
  double k_max = 0.0;
  for (Eigen::Index k = 0; k < K.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, k); it; ++it)
      k_max = std::max(k_max, std::abs(it.value()));
  }
  if (k_max == 0.0) k_max = 1.0;
  Eigen::VectorXd row_max = Eigen::VectorXd::Zero(m);
  for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      row_max[it.row()] = std::max(row_max[it.row()], std::abs(it.value()));
  }
  Eigen::VectorXd D(m);
  for (Eigen::Index i = 0; i < m; ++i) D[i] = row_max[i] > 0.0 ? k_max / row_max[i] : 1.0;

  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(K.nonZeros() + 2 * A.nonZeros()));
  for (Eigen::Index k = 0; k < K.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, k); it; ++it)
      trip.emplace_back(it.row(), it.col(), it.value());
  }
  for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      const double a = D[it.row()] * it.value();
      trip.emplace_back(n + it.row(), it.col(), a);
      trip.emplace_back(it.col(), n + it.row(), a);
    }
  }
  Eigen::SparseMatrix<double> S(n + m, n + m);
  S.setFromTriplets(trip.begin(), trip.end());
  S.makeCompressed();

  // A generic right-hand side: a near-null direction of a matrix is amplified by 1/(its pivot)
  // in the solve, so the solution shows the mechanism (and ‖S‖₁ ‖S⁻¹r‖₁ / ‖r‖₁ estimates S's
  // condition).
  std::mt19937 gen(20261125U);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd probe(n + m);
  for (Eigen::Index i = 0; i < n + m; ++i) probe[i] = uniform(gen);
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(S);
  if (lu.info() != Eigen::Success) {
    // SparseLU's own message names a column of the permuted matrix: no help to the user. The
    // DOFs of the mechanism are those of the null direction, which K's block shifted by 1e-10
    // of its largest entry makes solvable and dominant.
    Eigen::SparseMatrix<double> shift(n + m, n + m);  // a sparse sum: O(nnz) at any size
    std::vector<Eigen::Triplet<double>> diagonal;
    for (Eigen::Index i = 0; i < n; ++i) diagonal.emplace_back(i, i, 1e-10 * k_max);
    shift.setFromTriplets(diagonal.begin(), diagonal.end());
    const Eigen::SparseMatrix<double> shifted = S + shift;
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> near;
    near.compute(shifted);
    std::vector<int> dofs;
    if (near.info() == Eigen::Success) dofs = mode_dofs(near.solve(probe).head(n));
    throw NoStaticEquilibrium(
        "the stiffness is singular on the motions the constraints allow (an exact zero pivot in "
        "the sparse LU of [K Aᵀ; A 0])",
        dofs);
  }
  const Eigen::VectorXd x = lu.solve(probe);
  StaticEquilibrium out;
  out.condition = norm1(S) * x.lpNorm<1>() / probe.lpNorm<1>();
  if (!(out.condition <= kSingularCondition)) {
    std::ostringstream s;
    s.precision(2);
    s << "the stiffness is singular on the motions the constraints allow (condition estimate of "
         "the saddle-point matrix "
      << out.condition << ")";
    throw NoStaticEquilibrium(s.str(), mode_dofs(x.head(n)));
  }

  Eigen::VectorXd b(n + m);
  b.head(n) = f;
  b.tail(m) = D.cwiseProduct(g);
  Eigen::VectorXd y = lu.solve(b);
  y += lu.solve(b - S * y);  // one step of iterative refinement: the residual to roundoff
  out.u = y.head(n);
  out.lambda = D.cwiseProduct(y.tail(m));
  Eigen::VectorXd r = K * out.u - f;
  if (m > 0) r += A.transpose() * out.lambda;
  const double scale =
      std::max({f.lpNorm<Eigen::Infinity>(), k_max * out.u.lpNorm<Eigen::Infinity>(),
                std::numeric_limits<double>::min()});
  out.residual = r.lpNorm<Eigen::Infinity>() / scale;
  return out;
}

}  // namespace condyn
