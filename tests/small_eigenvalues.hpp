#pragma once
/// The eigenvalues of a 3 × 3 real matrix, by Eigen's EigenSolver (a real Schur form), compiled
/// once in the test support library: instantiating the solver took most of a test file's compile
/// time.

#include <Eigen/Dense>

namespace condyn::test {

/// a's eigenvalues, in EigenSolver's order.
Eigen::Vector3cd eigenvalues_3x3(const Eigen::Matrix3d& a);

}  // namespace condyn::test
