#include "tests/compare.hpp"

#include <sstream>

namespace condyn::test {

Mismatch compare_matrices(const Eigen::MatrixXd& got, const Eigen::MatrixXd& expected,
                          double rel_tol, double abs_tol) {
  Mismatch m;
  std::ostringstream s;
  s.precision(17);
  if (got.rows() != expected.rows() || got.cols() != expected.cols()) {
    s << "shape " << got.rows() << "x" << got.cols() << " vs expected " << expected.rows() << "x"
      << expected.cols();
    return {false, s.str()};
  }
  if (got.size() == 0) return m;
  const double tol = abs_tol + rel_tol * expected.cwiseAbs().maxCoeff();
  Eigen::Index i = 0, j = 0;
  const double worst = (got - expected).cwiseAbs().maxCoeff(&i, &j);
  if (!(worst <= tol)) {
    s << "worst entry (" << i << "," << j << "): got " << got(i, j) << ", expected "
      << expected(i, j) << ", |diff| " << worst << " > tol " << tol;
    return {false, s.str()};
  }
  return m;
}

}  // namespace condyn::test
