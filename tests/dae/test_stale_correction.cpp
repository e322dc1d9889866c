#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "dae/integrators/stale_correction.hpp"
#include "models/core/eigen_decompositions.hpp"

using namespace condyn;

namespace test_stale_correction {

namespace {

/// Six unknowns (0..3 differential, 4..5 algebraic) and six equations, 4 and 5 algebraic. The
/// algebraic rows over the differential unknowns: W = [1 2 0 0; 0 1 −1 3]; they also hold
/// entries of the algebraic unknowns' columns, which W leaves out.
Eigen::SparseMatrix<double> newton_matrix(double w10 = 0.0) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Identity(6, 6) * 5.0;
  J(0, 4) = 1.0;
  J(1, 5) = -2.0;
  J(4, 0) = 1.0;
  J(4, 1) = 2.0;
  J(5, 0) = w10;
  J(5, 1) = 1.0;
  J(5, 2) = -1.0;
  J(5, 3) = 3.0;
  J(4, 4) = 0.0;  // no algebraic unknown in the algebraic rows' differential part
  J(5, 5) = 0.0;
  return J.sparseView();
}

/// A correction with entries of both signs and sizes 0.3 to 9.
Eigen::VectorXd correction_vector() {
  Eigen::VectorXd x(6);
  x[0] = 0.3;
  x[1] = -1.2;
  x[2] = 2.5;
  x[3] = 0.7;
  x[4] = -4.0;
  x[5] = 9.0;
  return x;
}

const std::vector<bool> kAlgebraic = {false, false, false, false, true, true};

Eigen::VectorXd differential_id() {
  Eigen::VectorXd id = Eigen::VectorXd::Zero(6);
  id.head(4).setOnes();
  return id;
}

}  // namespace

TEST_CASE("stale correction: the algebraic rows see the unscaled correction, the rest is scaled") {
  StaleCorrection correction(kAlgebraic, differential_id());
  const Eigen::VectorXd x = correction_vector();
  // Before any matrix (IDA factors one before its first solve): left as solved.
  Eigen::VectorXd before = x;
  correction.apply(3.0, before);
  CHECK(before == x);
  const Eigen::SparseMatrix<double> J = newton_matrix();
  correction.update(J, 2.0);
  REQUIRE(correction.projects());

  // At the cj of the matrix: nothing changes.
  Eigen::VectorXd same = x;
  correction.apply(2.0, same);
  CHECK(same == x);

  // cj = 3 against cj₀ = 2: s = 2 / (1 + 1.5) = 0.8. The normal part of x's differential block
  // (computed here densely) stays, the tangential part is scaled by s, the multipliers stay.
  Eigen::VectorXd y = x;
  correction.apply(3.0, y);
  const double s = 0.8;
  const Eigen::MatrixXd W = Eigen::MatrixXd(J).block(4, 0, 2, 4);
  const Eigen::VectorXd xd = x.head(4);
  const Eigen::VectorXd normal = W.transpose() * (W * W.transpose()).ldlt().solve(W * xd);
  const Eigen::VectorXd expected = normal + s * (xd - normal);
  // One 2 x 2 solve and a few products of O(10) entries: 1e-14 of x's size.
  CHECK((y.head(4) - expected).cwiseAbs().maxCoeff() <= 1e-14 * x.cwiseAbs().maxCoeff());
  CHECK((W * y.head(4) - W * xd).cwiseAbs().maxCoeff() <= 1e-14 * x.cwiseAbs().maxCoeff());
  CHECK(y.tail(2) == x.tail(2));
  // Not a plain scaling: the tangential part moved.
  CHECK((y.head(4) - xd).norm() > 0.1 * (1.0 - s) * xd.norm());
}

TEST_CASE("stale correction: differential unknowns in several runs, as in the contiguous case") {
  // The same system with its unknowns reordered [d0 a4 d1 d2 a5 d3]: the differential unknowns
  // form the runs [0, 1), [2, 4) and [5, 6). The result is the contiguous one, reordered.
  const std::vector<int> position = {0, 2, 3, 5, 1, 4};  // old unknown -> new position
  const Eigen::SparseMatrix<double> J = newton_matrix();
  Eigen::MatrixXd reordered = Eigen::MatrixXd::Zero(6, 6);
  for (int c = 0; c < 6; ++c) reordered.col(position[c]) = Eigen::MatrixXd(J).col(c);
  Eigen::VectorXd id = Eigen::VectorXd::Zero(6);
  Eigen::VectorXd x(6);
  const Eigen::VectorXd x0 = correction_vector();
  for (int c = 0; c < 6; ++c) {
    id[position[c]] = c < 4 ? 1.0 : 0.0;
    x[position[c]] = x0[c];
  }
  StaleCorrection contiguous(kAlgebraic, differential_id());
  contiguous.update(J, 2.0);
  StaleCorrection runs(kAlgebraic, id);
  runs.update(Eigen::SparseMatrix<double>(reordered.sparseView()), 2.0);
  REQUIRE(runs.projects());
  Eigen::VectorXd expected = x0;
  contiguous.apply(3.0, expected);
  runs.apply(3.0, x);
  for (int c = 0; c < 6; ++c) {
    CHECK(std::abs(x[position[c]] - expected[c]) <= 1e-15 * x0.cwiseAbs().maxCoeff());
  }
  // The algebraic unknowns stay as solved.
  CHECK(x[1] == x0[4]);
  CHECK(x[4] == x0[5]);
}

TEST_CASE("stale correction: dependent or empty algebraic rows fall back to IDA's scaling") {
  const Eigen::VectorXd x = correction_vector();
  SUBCASE("rows W = [1 2 0 0; 1 2 0 0] are dependent") {
    Eigen::SparseMatrix<double> J = newton_matrix();
    J.coeffRef(5, 0) = 1.0;
    J.coeffRef(5, 1) = 2.0;
    J.coeffRef(5, 2) = 0.0;
    J.coeffRef(5, 3) = 0.0;
    StaleCorrection correction(kAlgebraic, differential_id());
    correction.update(J, 2.0);
    CHECK_FALSE(correction.projects());
    Eigen::VectorXd y = x;
    correction.apply(3.0, y);
    CHECK((y - 0.8 * x).cwiseAbs().maxCoeff() <= 1e-15 * x.cwiseAbs().maxCoeff());
  }
  SUBCASE("nearly dependent: 1e-7 apart (pivot 1e-14 of the largest)") {
    Eigen::SparseMatrix<double> J = newton_matrix();
    J.coeffRef(5, 0) = 1.0;
    J.coeffRef(5, 1) = 2.0 + 1e-7;
    J.coeffRef(5, 2) = 0.0;
    J.coeffRef(5, 3) = 0.0;
    StaleCorrection correction(kAlgebraic, differential_id());
    correction.update(J, 2.0);
    CHECK_FALSE(correction.projects());
  }
  SUBCASE("an algebraic row without differential unknowns") {
    Eigen::SparseMatrix<double> J = newton_matrix();
    for (int c = 0; c < 4; ++c) J.coeffRef(5, c) = 0.0;
    StaleCorrection correction(kAlgebraic, differential_id());
    correction.update(J, 2.0);
    CHECK_FALSE(correction.projects());
  }
  SUBCASE("a later matrix with independent rows projects again") {
    Eigen::SparseMatrix<double> J = newton_matrix();
    for (int c = 0; c < 4; ++c) J.coeffRef(5, c) = 0.0;
    StaleCorrection correction(kAlgebraic, differential_id());
    correction.update(J, 2.0);
    CHECK_FALSE(correction.projects());
    correction.update(newton_matrix(0.5), 2.0);
    CHECK(correction.projects());
  }
}

}  // namespace test_stale_correction
