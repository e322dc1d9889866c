// The largest frequency of models beyond the dense eigensolver
// (dae/formulations/largest_frequency.hpp): what Lanczos declines. Its value against the dense
// eigensolver is in test_largest_frequency_validation.cpp.

#include <doctest/doctest.h>

#include "dae/formulations/largest_frequency.hpp"
#include "tests/spring_chain.hpp"

using namespace condyn;

namespace test_largest_frequency {

TEST_CASE("Lanczos declines a singular mass matrix instead of dividing by zero") {
  Eigen::SparseMatrix<double> K, M;
  test::spring_chain(600, K, M);
  M.coeffRef(10, 10) = 0.0;  // a massless DOF: M is not positive definite
  CHECK_FALSE(largest_eigenvalue(K, M).has_value());
}

}  // namespace test_largest_frequency
