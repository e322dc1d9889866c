#pragma once
/// What the fixed-step schemes (the Newmark family, RATTLE) share on the integration loop
/// (dae/integrators/step_driver.hpp): the step grid t0 + k h, and the cubic Hermite interpolant
/// of (u, v) between a step's ends.
///
/// Grid: a step ends at the next grid point, or at the stop time (a load step, the end of the
/// run) when that comes first, after which the steps return to the grid. An output time within
/// roundoff of a grid point is that grid point, so that the output is a step result.

#include <Eigen/Dense>

namespace condyn {

class FixedStepGrid {
 public:
  /// The grid t0 + k h (h > 0).
  FixedStepGrid(double t0, double h) : t0_(t0), h_(h) {}

  /// The end of the step from t (a grid point, or a stop time off the grid): the next grid point
  /// (the output time `tout` itself when it lies within roundoff of it), or `stop` when it comes
  /// first. A stop within a millionth of h after a grid point is reached in one step slightly
  /// longer than h rather than by a step of roundoff size.
  [[nodiscard]] double next_time(double t, double stop, double tout);
  /// The length of the step from t to t_next: h itself when they differ by roundoff (a linear
  /// model's Newton matrix depends on the step alone and stays factored), else t_next − t.
  [[nodiscard]] double step_length(double t, double t_next) const;
  [[nodiscard]] double step() const { return h_; }

 private:
  double t0_, h_;
  long index_ = 0;  ///< the last grid point t0 + k h reached or passed
};

/// u and v at s ∈ [0, 1] of a step of length h from (u0, v0) to (u1, v1): the cubic Hermite
/// interpolant of u (exact at the ends, with the end velocities as its slopes) and its
/// derivative; `acc` its second derivative (linear in s).
void hermite(double s, double h, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0,
             const Eigen::VectorXd& u1, const Eigen::VectorXd& v1, Eigen::VectorXd& u,
             Eigen::VectorXd& v, Eigen::VectorXd* acc = nullptr);

}  // namespace condyn
