#pragma once
/// How far a trajectory is from a reference: relative max-norms over every DOF and output time,
/// ‖x − x_ref‖_max / ‖x_ref‖_max (absolute when the reference is identically zero).

#include "dae/trajectory.hpp"

namespace condyn {

struct TrajectoryError {
  double displacement = 0.0, velocity = 0.0, reaction = 0.0;
  [[nodiscard]] double worst() const;
};

/// Both trajectories must share output times; throws std::invalid_argument otherwise.
[[nodiscard]] TrajectoryError relative_error(const Trajectory& run, const Trajectory& reference);

}  // namespace condyn
