// The fixed Jacobian pattern built from declared blocks (dae/linsolve/block_jacobian.hpp).

#include <doctest/doctest.h>

#include <Eigen/Sparse>
#include <stdexcept>
#include <vector>

#include "dae/linsolve/block_jacobian.hpp"

using namespace condyn;

namespace test_block_jacobian {

TEST_CASE(
    "BlockJacobian: the union of the blocks' patterns and the diagonal, values added in place") {
  using Sparse = Eigen::SparseMatrix<double>;
  Sparse S(2, 3);  // entries (0,0), (1,0), (0,2); an explicit zero (1,2) is part of the pattern
  S.insert(0, 0) = 1.0;
  S.insert(1, 0) = 2.0;
  S.insert(0, 2) = 3.0;
  S.insert(1, 2) = 0.0;
  S.makeCompressed();
  BlockJacobian blocks(5);
  blocks.declare(0, 0, S);
  blocks.declare(1, 2, S);  // overlaps the first at (1,2)
  blocks.declare_identity(3, 0, 2);
  blocks.finish();
  const JacobianPattern& pattern = blocks.pattern();
  REQUIRE(pattern.outer.size() == 6);
  CHECK(pattern.nonZeros() == static_cast<Eigen::Index>(pattern.inner.size()));
  Sparse J = pattern.matrix();
  REQUIRE(J.isCompressed());
  // The expected pattern, from a dense mask.
  Eigen::MatrixXi mask = Eigen::MatrixXi::Zero(5, 5);
  for (int k = 0; k < 5; ++k) mask(k, k) = 1;  // the diagonal is always there
  for (const auto& [r0, c0] : {std::pair{0, 0}, {1, 2}}) {
    mask(r0 + 0, c0 + 0) = mask(r0 + 1, c0 + 0) = mask(r0 + 0, c0 + 2) = mask(r0 + 1, c0 + 2) = 1;
  }
  mask(3, 0) = mask(4, 1) = 1;
  CHECK(J.nonZeros() == mask.sum());
  for (int j = 0; j < 5; ++j) {
    int previous = -1;
    for (Sparse::InnerIterator it(J, j); it; ++it) {
      CHECK(mask(it.row(), j) == 1);
      CHECK(it.row() > previous);  // sorted, no repeats
      CHECK(it.value() == 0.0);
      previous = static_cast<int>(it.row());
    }
  }
  JacobianMap view = map_of(J);
  BlockJacobian::add(view, 0, 0, S, 2.0);
  BlockJacobian::add(view, 1, 2, S, 1.0);
  BlockJacobian::add_identity(view, 0, 0, 5, 1.0);
  CHECK(J.coeff(0, 0) == 3.0);  // 2·1 + 1
  CHECK(J.coeff(1, 2) == 1.0);  // 2 S(1,2) = 0 from the first block, S(0,0) = 1 from the second
  CHECK(J.coeff(1, 1) == 1.0);  // the identity only
  CHECK(J.coeff(2, 4) == 0.0);
  // The same fill on values held outside the pattern (the integrator's matrix).
  std::vector<double> values(static_cast<std::size_t>(pattern.nonZeros()), 0.0);
  JacobianMap outer_view = pattern.map(values.data());
  BlockJacobian::add(outer_view, 0, 0, S, 2.0);
  BlockJacobian::add(outer_view, 1, 2, S, 1.0);
  BlockJacobian::add_identity(outer_view, 0, 0, 5, 1.0);
  for (Eigen::Index k = 0; k < J.nonZeros(); ++k) {
    CHECK(values[static_cast<std::size_t>(k)] == J.valuePtr()[k]);
  }
  Sparse outside(1, 1);
  outside.insert(0, 0) = 1.0;
  CHECK_THROWS_AS(BlockJacobian::add(view, 4, 3, outside), std::logic_error);  // (4,3) not declared

  BlockJacobian too_wide(3);
  too_wide.declare(0, 1, S);  // columns 1..3 of a 3 x 3 matrix
  CHECK_THROWS_AS(too_wide.finish(), std::logic_error);
  BlockJacobian too_tall(3);
  too_tall.declare(2, 0, S);  // rows 2..3
  CHECK_THROWS_AS(too_tall.finish(), std::logic_error);
}

}  // namespace test_block_jacobian
