#pragma once
/// Recorded ground accelerations ([ground_motion] acceleration with table terms): each record's
/// peak over the run, for the run's summary, and what the record's name says of its unit, so that
/// a record in g run without its scale (9.81 times too small) or with a scale for another unit
/// (981: cm/s² in a scene in metres) does not run silently (docs/scenes.md, "Ground motion
/// records: peaks and unit warnings").

#include <string>

#include "models/core/time_function.hpp"

namespace condyn {

/// Standard gravity in m/s²: g in a scene that says `units = "SI"`.
inline constexpr double kStandardGravity = 9.80665;
/// A scale within this relative distance of g counts as g: in SI 9.51 to 10.10, so 9.8, 9.81 and
/// 10 are g, 981 (cm/s²) and 1 (no scale) are not.
inline constexpr double kScaleNearG = 0.03;
/// An SI record peaking above this many g is warned of: beyond the largest ground acceleration
/// ever recorded (about 4 g, Iwate-Miyagi 2008), so far more likely a unit or scale slip.
inline constexpr double kMaxPlausiblePeakG = 5.0;

/// The peak of |term(t)| over [0, t_end] and the first time it is reached. A table is piecewise
/// linear and constant outside its samples, so the peak lies at t = 0, t = t_end or a sample.
struct RecordPeak {
  double value = 0.0;  ///< term(t) at the peak, signed, in the scene's units (scale applied)
  double t = 0.0;
};
[[nodiscard]] RecordPeak record_peak(const TimeTerm& table_term, double t_end);

/// Whether a column or file name says its values are in g: it holds the word "g" (either case)
/// between characters that are not letters or digits ("acceleration_g", "acc (g)", "PGA-G.csv",
/// "g"); "gal", "deg", "avg" do not.
[[nodiscard]] bool name_says_g(const std::string& name);

/// Whether `scale` is g in a common unit of length per s² (m, cm, mm, ft, in), within
/// kScaleNearG; with `si`, in m/s² only.
[[nodiscard]] bool scale_is_g(double scale, bool si);

}  // namespace condyn
