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

Eigen::MatrixXd finite_difference_jacobian(const DaeProblem& dae, double t,
                                           const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                           double cj) {
  const int n = dae.size();
  const double h = 1e-6;
  Eigen::MatrixXd fd(n, n);
  Eigen::VectorXd rp(n), rm(n);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd y1 = y, y2 = y, yp1 = yp, yp2 = yp;
    y1[j] += h;
    y2[j] -= h;
    yp1[j] += cj * h;
    yp2[j] -= cj * h;
    dae.residual(t, y1, yp1, rp);
    dae.residual(t, y2, yp2, rm);
    fd.col(j) = (rp - rm) / (2 * h);
  }
  return fd;
}

double least_squares_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k];
    sy += y[k];
    sxx += x[k] * x[k];
    sxy += x[k] * y[k];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace condyn::test
