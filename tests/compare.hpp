#pragma once
/// The one comparison helper of the test suite: on failure it names the worst entry, both values
/// and the tolerance.

#include <Eigen/Dense>
#include <string>

namespace condyn::test {

struct Mismatch {
  bool ok = true;
  std::string message;  ///< "worst entry (2,1): got 3.5, expected 3.4, |diff| 0.1 > tol 1e-9"
};

/// Entry-wise |a − b| <= abs_tol + rel_tol * max|b|.
[[nodiscard]] Mismatch compare_matrices(const Eigen::MatrixXd& got, const Eigen::MatrixXd& expected,
                                        double rel_tol, double abs_tol = 0.0);

}  // namespace condyn::test

/// CHECK that two matrices agree; prints the worst entry when they do not.
#define CONDYN_CHECK_CLOSE(got, expected, rel_tol)                                      \
  do {                                                                                  \
    const auto condyn_m = condyn::test::compare_matrices((got), (expected), (rel_tol)); \
    CHECK_MESSAGE(condyn_m.ok, condyn_m.message);                                       \
  } while (0)
