// Singular values (models/core/singular_values.hpp), by the symmetric eigenvalue path (small
// blocks) and by LAPACK's dgesdd (large ones): against matrices built from known singular values, U
// diag(σ) Vᵀ with U and V orthogonal (Householder reflections, so the construction itself needs no
// SVD).
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "models/core/singular_values.hpp"

using namespace condyn;

namespace test_singular_values {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// The Householder reflection I − 2 w wᵀ / wᵀw of w = (1, 2, ..., n) + shift: orthogonal.
Eigen::MatrixXd reflection(Eigen::Index n, double shift) {
  const Eigen::VectorXd w =
      Eigen::VectorXd::LinSpaced(n, 1.0, static_cast<double>(n)).array() + shift;
  return Eigen::MatrixXd::Identity(n, n) - 2.0 * w * w.transpose() / w.squaredNorm();
}

/// An m x n matrix whose singular values are `sigma` (min(m, n) of them).
Eigen::MatrixXd with_singular_values(Eigen::Index m, Eigen::Index n, const Eigen::VectorXd& sigma) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(m, n);
  d.diagonal() = sigma;
  return reflection(m, 0.5) * d * reflection(n, -0.25);
}

}  // namespace

TEST_CASE("singular_values: known values of square and rectangular matrices, largest first") {
  const std::pair<Eigen::Index, Eigen::Index> shapes[] = {
      {1, 1}, {4, 4}, {6, 3}, {3, 7}, {40, 40}, {150, 150}, {160, 120}, {101, 130}};
  for (const auto& shape : shapes) {
    const Eigen::Index m = shape.first, n = shape.second;
    CAPTURE(m);
    CAPTURE(n);
    const Eigen::Index k = std::min(m, n);
    // Spread over twelve decades: the small ones are what a condition number needs.
    Eigen::VectorXd sigma(k);
    for (Eigen::Index i = 0; i < k; ++i)
      sigma[i] = std::pow(10.0, -12.0 * i / std::max<Eigen::Index>(1, k - 1));
    const Eigen::VectorXd s = singular_values(with_singular_values(m, n, sigma));
    REQUIRE(s.size() == k);
    // A backward-stable SVD errs by a few eps times the largest value (here 1), absolutely; the
    // construction's own roundoff is of the same size: 100 eps.
    for (Eigen::Index i = 0; i < k; ++i) {
      CAPTURE(i);
      CHECK(std::abs(s[i] - sigma[i]) <= 100 * kEps);
      if (i > 0) CHECK(s[i] <= s[i - 1]);
    }
  }
}

TEST_CASE("singular_values: the symmetric path and LAPACK's agree on a block LAPACK takes") {
  Eigen::VectorXd sigma(120);
  for (Eigen::Index i = 0; i < sigma.size(); ++i) sigma[i] = std::pow(10.0, -0.1 * i);
  const Eigen::MatrixXd a = with_singular_values(150, 120, sigma);
  REQUIRE(std::min(a.rows(), a.cols()) > kSymmetricSingularValuesMax);
  const Eigen::VectorXd lapack = singular_values(a), symmetric = symmetric_singular_values(a);
  REQUIRE(lapack.size() == 120);
  REQUIRE(symmetric.size() == 120);
  // Both backward stable: each within a few eps of σ_max = 1 of the exact values.
  CHECK((lapack - symmetric).cwiseAbs().maxCoeff() <= 100 * kEps);
}

TEST_CASE("singular_values: a block 3 x 100,000 takes the work of its three values") {
  // Its long side reduced by QR first: [0 A; Aᵀ 0] would be 100,003 x 100,003 (80 GB dense).
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3, 100000);
  a(0, 5) = 3.0;
  a(1, 70000) = 2.0;
  a(2, 99999) = 0.5;
  a(2, 5) = 1e-3;  // couples rows 0 and 2: σ from the 2 x 2 block [[3, 0], [1e-3, 0.5]]
  const Eigen::VectorXd s = symmetric_singular_values(a);
  REQUIRE(s.size() == 3);
  // Of [[3, 0], [1e-3, 0.5]]: σ₁² + σ₂² = the sum of squares S, σ₁ σ₂ = |det| = 1.5.
  const double sum = 9.0 + 1e-6 + 0.25, det = 1.5;
  const double big = std::sqrt(0.5 * (sum + std::sqrt(sum * sum - 4.0 * det * det)));
  const Eigen::Vector2d exact(big, det / big);
  CHECK(std::abs(s[0] - exact[0]) <= 100 * kEps * exact[0]);
  CHECK(std::abs(s[1] - 2.0) <= 100 * kEps * exact[0]);
  CHECK(std::abs(s[2] - exact[1]) <= 100 * kEps * exact[0]);
  CHECK((singular_values(a.transpose()) - s).cwiseAbs().maxCoeff() <= 100 * kEps * exact[0]);
}

TEST_CASE("singular_values: a rank-deficient block, an empty one, and a value not finite") {
  // Two equal rows: the smallest value is 0 to roundoff of the largest.
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3, 3);
  a.row(0) << 1.0, 2.0, 3.0;
  a.row(1) = a.row(0);
  a.row(2) << 0.0, 1.0, -1.0;
  const Eigen::VectorXd s = singular_values(a);
  CHECK(s[2] <= 10 * kEps * s[0]);
  // ‖a‖_F² is the sum of the squares of the values.
  CHECK(s.squaredNorm() == doctest::Approx(a.squaredNorm()).epsilon(10 * kEps));
  CHECK(singular_values(Eigen::MatrixXd(0, 3)).size() == 0);
  // Two equal columns of a block LAPACK takes.
  Eigen::MatrixXd wide = Eigen::MatrixXd::Zero(110, 110);
  wide.diagonal().setOnes();
  wide.col(7) = wide.col(3);
  CHECK(singular_values(wide)[109] <= 10 * kEps);
  a(1, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS((void)singular_values(a), std::runtime_error);
  wide(5, 5) = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS((void)singular_values(wide), std::runtime_error);
}

}  // namespace test_singular_values
