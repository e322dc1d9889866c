#pragma once
/// The one comparison helper of the test suite: on failure it names the worst entry, both values
/// and the tolerance.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "dae/interface/dae_problem.hpp"

namespace condyn::test {

struct Mismatch {
  bool ok = true;
  std::string message;  ///< "worst entry (2,1): got 3.5, expected 3.4, |diff| 0.1 > tol 1e-9"
};

/// Entry-wise |a − b| <= abs_tol + rel_tol * max|b|.
[[nodiscard]] Mismatch compare_matrices(const Eigen::MatrixXd& got, const Eigen::MatrixXd& expected,
                                        double rel_tol, double abs_tol = 0.0);

/// Central differences of a DAE residual along (y + h e_j, y' + cj h e_j): column j of
/// dF/dy + cj dF/dy', the matrix IDA asks for. h = 1e-6 suits O(1) states.
[[nodiscard]] Eigen::MatrixXd finite_difference_jacobian(const DaeProblem& dae, double t,
                                                         const Eigen::VectorXd& y,
                                                         const Eigen::VectorXd& yp, double cj);

/// Least-squares slope of y against x (observed orders of convergence).
[[nodiscard]] double least_squares_slope(const std::vector<double>& x,
                                         const std::vector<double>& y);

}  // namespace condyn::test

/// CHECK that two matrices agree; prints the worst entry when they do not.
#define CONDYN_CHECK_CLOSE(got, expected, rel_tol)                                      \
  do {                                                                                  \
    const auto condyn_m = condyn::test::compare_matrices((got), (expected), (rel_tol)); \
    CHECK_MESSAGE(condyn_m.ok, condyn_m.message);                                       \
  } while (0)
