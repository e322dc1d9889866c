// The largest frequency of models beyond the dense eigensolver
// (dae/formulations/largest_frequency.hpp): the Lanczos value against the dense generalized
// eigensolver on chains small enough for both (a dense 600 x 600 pencil: the validation tier).

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>

#include "dae/formulations/largest_frequency.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "tests/spring_chain.hpp"

using namespace condyn;

namespace test_largest_frequency_validation {

TEST_CASE("Lanczos finds the largest eigenvalue of K x = w^2 M x to its tolerance") {
  for (const int n : {50, 600}) {
    CAPTURE(n);
    Eigen::SparseMatrix<double> K, M;
    test::spring_chain(n, K, M);
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

}  // namespace test_largest_frequency_validation
