#include "validation/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace condyn {

double TrajectoryError::worst() const { return std::max({displacement, velocity, reaction}); }

namespace {

double relative_max(const Eigen::MatrixXd& a, const Eigen::MatrixXd& ref) {
  if (a.size() == 0) return 0.0;
  const double diff = (a - ref).cwiseAbs().maxCoeff();
  const double scale = ref.cwiseAbs().maxCoeff();
  return scale > 0.0 ? diff / scale : diff;
}

}  // namespace

TrajectoryError relative_error(const Trajectory& run, const Trajectory& reference) {
  if (run.t.size() != reference.t.size() || run.u.rows() != reference.u.rows()) {
    throw std::invalid_argument("relative_error: trajectories differ in shape");
  }
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    if (std::abs(run.t[k] - reference.t[k]) > 1e-12 * std::max(1.0, std::abs(reference.t[k]))) {
      throw std::invalid_argument("relative_error: output times differ");
    }
  }
  return {relative_max(run.u, reference.u), relative_max(run.v, reference.v),
          relative_max(run.reaction, reference.reaction)};
}

}  // namespace condyn
