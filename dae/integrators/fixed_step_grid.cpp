#include "dae/integrators/fixed_step_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace condyn {

namespace {

/// A stop within this fraction of h after a grid point is reached from the point before it, in
/// one step slightly longer than h, rather than by a step of roundoff size after the grid point.
constexpr double kGridSlack = 1e-6;
/// An output time this many ulps of the time from a grid point is that grid point: k · output_step
/// and j · h differ by a few ulps where they mean the same time.
constexpr double kOutputUlps = 64.0;

}  // namespace

double FixedStepGrid::next_time(double t, double stop, double tout) {
  const double slack = kGridSlack * h_;
  // The grid points at or within slack after t are passed (t is one of them, or a stop).
  while (t0_ + static_cast<double>(index_ + 1) * h_ <= t + slack) ++index_;
  const double grid_next = t0_ + static_cast<double>(index_ + 1) * h_;
  if (grid_next < stop - slack) {
    ++index_;
    // An output time within roundoff of the grid point (k · output_step against t0 + j h) is
    // the step's end itself, so that the output is the step's result.
    const double roundoff =
        kOutputUlps * std::numeric_limits<double>::epsilon() * std::max(std::abs(grid_next), h_);
    return std::abs(tout - grid_next) <= roundoff ? tout : grid_next;
  }
  return stop;
}

double FixedStepGrid::step_length(double t, double t_next) const {
  const double h = t_next - t;
  const double roundoff =
      kOutputUlps * std::numeric_limits<double>::epsilon() * std::max(std::abs(t_next), h);
  return std::abs(h - h_) <= roundoff ? h_ : h;
}

void hermite(double s, double h, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0,
             const Eigen::VectorXd& u1, const Eigen::VectorXd& v1, Eigen::VectorXd& u,
             Eigen::VectorXd& v, Eigen::VectorXd* acc) {
  // Cubic Hermite basis on s ∈ [0, 1] and its first and second derivatives in s.
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
  const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -d00, d11 = 3 * s2 - 2 * s;
  u = h00 * u0 + (h10 * h) * v0 + h01 * u1 + (h11 * h) * v1;
  v = (d00 / h) * u0 + d10 * v0 + (d01 / h) * u1 + d11 * v1;
  if (acc != nullptr) {
    const double e00 = 12 * s - 6, e10 = 6 * s - 4, e01 = -e00, e11 = 6 * s - 2;
    *acc = (e00 / (h * h)) * u0 + (e10 / h) * v0 + (e01 / (h * h)) * u1 + (e11 / h) * v1;
  }
}

}  // namespace condyn
