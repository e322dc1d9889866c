#pragma once
/// How far a trajectory is from a reference: relative max-norms over every DOF and output time,
/// ‖x − x_ref‖_max / ‖x_ref‖_max (absolute when the reference is identically zero); velocities
/// against at least ‖u_ref‖_max / (t_last − t_first), so that a structure at rest is not judged
/// by the roundoff of its reference's velocities.

#include <optional>
#include <string>

#include "dae/run/trajectory.hpp"

namespace condyn {

struct TrajectoryError {
  double displacement = 0.0, velocity = 0.0, reaction = 0.0;
  [[nodiscard]] double worst() const;
};

/// What errors are measured against: each quantity's largest magnitude over every DOF and row of
/// a trajectory (a whole run, where compare samples its reference between the output rows, so
/// that a quantity zero at every output row still has its scale).
struct ErrorScales {
  double displacement = 0.0, velocity = 0.0, reaction = 0.0;
  /// energy_error_scale: max(|E(0)|, max_t T(t), the model's energy scale), the scale of
  /// relative_energy_error; 0 without energies.
  double energy = 0.0;
};

/// The scales of `trajectory`: max |u|, max |f_con| (over the rows not flagged near_singular, whose
/// reactions the state does not determine), max |u'| but at least max |u| / (t_last −
/// t_first) (so that a structure at rest is not judged by the roundoff of its velocities: any
/// motion of angular frequency ω over a span D ≥ 2π/ω has max |u'| ≈ ω max |u| > max |u| / D), and
/// the energy scale.
[[nodiscard]] ErrorScales error_scales(const Trajectory& trajectory);

/// Both trajectories must share output times; throws std::invalid_argument otherwise. Relative to
/// error_scales(reference).
[[nodiscard]] TrajectoryError relative_error(const Trajectory& run, const Trajectory& reference);
/// The same relative to `scales`: max-norm differences over every DOF and output time divided by
/// the scale (absolute where the scale is 0: a quantity that is zero throughout); reactions over
/// the output times that neither trajectory flags near_singular (0 when both flag every one).
[[nodiscard]] TrajectoryError relative_error(const Trajectory& run, const Trajectory& reference,
                                             const ErrorScales& scales);
/// max_t |E(t) − E(0)| of `run` over max(energy_scale, its own energy_error_scale): −1 without
/// energies, NaN when an energy leaves the double range (relative_energy_error's rules).
[[nodiscard]] double relative_energy_error(const Trajectory& run, double energy_scale);

/// The Test Set for IVP Solvers' "mixed-error significant correct digits" (Mazzia, Magherini,
/// Iavernaro, release 2.4): min_i −log10(|y_i − ref_i| / (atol/rtol + |ref_i|)), with the run's
/// own rtol and atol. Exact agreement counts as 17 digits (beyond double precision).
[[nodiscard]] double mescd(const Eigen::VectorXd& y, const Eigen::VectorXd& ref, double rtol,
                           double atol);

/// A run scored against a built-in model's published reference at its final time.
struct ReferenceScore {
  double t = 0.0;
  /// mescd of positions, and of velocities when the reference has them (mescd may be negative: an
  /// error larger than the value itself).
  double digits_u = 0.0;
  std::optional<double> digits_v;
  int trusted_u = 0, trusted_v = 0;  ///< what the reference vouches for
  std::string source;
  /// "8.9 digits in positions, 8.1 in velocities"; digits beyond the reference's trust are
  /// reported as "≥ trusted (the reference's limit)".
  [[nodiscard]] std::string describe() const;
};

/// The score at output column k, when the model has a reference at that time.
[[nodiscard]] std::optional<ReferenceScore> score_at_output(const Model& model,
                                                            const Trajectory& run, std::size_t k,
                                                            double rtol, double atol);

/// The score at the trajectory's last time, when the model has a reference there.
[[nodiscard]] std::optional<ReferenceScore> score_against_reference(const Model& model,
                                                                    const Trajectory& run,
                                                                    double rtol, double atol);

}  // namespace condyn
