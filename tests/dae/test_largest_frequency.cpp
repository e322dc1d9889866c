// The largest frequency of models beyond the dense eigensolver
// (dae/formulations/largest_frequency.hpp): the Lanczos value against the dense generalized
// eigensolver on a model small enough for both.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "dae/formulations/largest_frequency.hpp"
#include "models/core/eigen_decompositions.hpp"

using namespace condyn;

namespace {

/// A fixed-free chain of n masses m_i = 1 + 0.5 sin(i) and springs k_i = 1 + 0.3 cos(2i):
/// distinct frequencies with a clustered top, the hard case for Lanczos.
void chain(int n, Eigen::SparseMatrix<double>& K, Eigen::SparseMatrix<double>& M) {
  std::vector<Eigen::Triplet<double>> k, m;
  for (int i = 0; i < n; ++i) {
    m.emplace_back(i, i, 1.0 + 0.5 * std::sin(i));
    const double below = 1.0 + 0.3 * std::cos(2.0 * i);  // spring to i-1 (or the ground)
    k.emplace_back(i, i, below);
    if (i > 0) {
      k.emplace_back(i - 1, i - 1, below);
      k.emplace_back(i - 1, i, -below);
      k.emplace_back(i, i - 1, -below);
    }
  }
  K.resize(n, n);
  M.resize(n, n);
  K.setFromTriplets(k.begin(), k.end());
  M.setFromTriplets(m.begin(), m.end());
}

}  // namespace

TEST_CASE("Lanczos finds the largest eigenvalue of K x = w^2 M x to its tolerance") {
  for (const int n : {50, 600}) {
    CAPTURE(n);
    Eigen::SparseMatrix<double> K, M;
    chain(n, K, M);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(
        Eigen::MatrixXd(K), Eigen::MatrixXd(M), Eigen::EigenvaluesOnly);
    const double exact = dense.eigenvalues().maxCoeff();
    const auto lanczos = largest_eigenvalue(K, M);
    REQUIRE(lanczos.has_value());
    // Spectra's test is on the Ritz residual, which bounds the eigenvalue's error by the same
    // relative size (symmetric pencil): kLargestFrequencyTolerance, observed far below it.
    CHECK(std::abs(*lanczos - exact) <= kLargestFrequencyTolerance * exact);
  }
}

TEST_CASE("Lanczos declines a singular mass matrix instead of dividing by zero") {
  Eigen::SparseMatrix<double> K, M;
  chain(600, K, M);
  M.coeffRef(10, 10) = 0.0;  // a massless DOF: M is not positive definite
  CHECK_FALSE(largest_eigenvalue(K, M).has_value());
}
