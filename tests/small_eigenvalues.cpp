#include "tests/small_eigenvalues.hpp"

#include <Eigen/Eigenvalues>

namespace condyn::test {

Eigen::Vector3cd eigenvalues_3x3(const Eigen::Matrix3d& a) { return a.eigenvalues(); }

}  // namespace condyn::test
