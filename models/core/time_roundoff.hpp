#pragma once
/// Roundoff of a run's time axis: times closer than it are the same time (an output time and a
/// load step, two load steps, a multiple of output_step and t_end).

#include <algorithm>
#include <cmath>
#include <limits>

namespace condyn {

inline constexpr double kTimeMergeUlps = 256.0;

/// kTimeMergeUlps × eps × max(|t0|, |t_end|, t_end − t0).
[[nodiscard]] inline double time_merge_tolerance(double t0, double t_end) {
  const double scale = std::max({std::abs(t0), std::abs(t_end), t_end - t0});
  return kTimeMergeUlps * std::numeric_limits<double>::epsilon() * scale;
}

}  // namespace condyn
