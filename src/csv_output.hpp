#pragma once
/// The CSV of the contract (scene-format.md, "Output"): first column t, then the requested
/// quantities in the order the scene lists them.

#include <functional>
#include <ostream>
#include <string>

#include "dae/trajectory.hpp"
#include "models/model.hpp"

namespace condyn {

/// Writes through a temporary file beside `path`, renamed into place only after a complete write:
/// a failure never leaves a half-written or clobbered file. A symbolic link is followed (the file
/// it names is replaced, the link stays); a device, FIFO or socket (/dev/null, /dev/stdout) is
/// written into directly, never replaced. Throws std::runtime_error naming path.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& writer);

/// Writes the CSV to a temporary file beside `path` and renames it into place, so a failed run
/// never leaves a half-written or clobbered file. Throws std::runtime_error naming the path.
void write_csv_atomically(const std::string& path, const Model& model, const Trajectory& traj);

/// The per-step drift log (run --steps-out): columns t, drift_position, drift_velocity, one row per
/// internal step of the integrator. Written atomically like the main CSV.
void write_steps_csv_atomically(const std::string& path, const Trajectory& traj);

}  // namespace condyn
