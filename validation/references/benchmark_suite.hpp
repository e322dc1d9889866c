#pragma once
/// The published benchmarks of `condyn validate` (../shared/reference/external-benchmarks.md):
/// Andrews' squeezing mechanism and the car axis from the Test Set for IVP Solvers (release 2.4),
/// and the pendulum of period 2. Each case is data: an embedded scene (validation/scenes/
/// benchmark_*.toml, whose [solve] names the required scheme and tolerance), the times at which
/// it is scored against the published or exact state, and the digits it must reach there.

#include <ostream>
#include <string>
#include <vector>

namespace condyn {

struct PublishedCase {
  std::string scene;          ///< embedded scene stem
  std::vector<double> times;  ///< output times at which the reference is known and scored
  /// The test set's mescd of the positions that the scene's scheme must reach at times[0]...
  double required_digits = 0.0;
  /// ...less this many per decade of t / times[0] (the pendulum: an oscillator's phase error,
  /// hence the global error, grows linearly with time, one digit per decade).
  double digits_lost_per_decade = 0.0;
  /// Also run the other multiplier schemes, for the report (cheap cases only).
  bool report_other_schemes = false;
  std::string reason;  ///< where the requirement comes from (printed: no figures that go stale)
};

[[nodiscard]] const std::vector<PublishedCase>& published_cases();

/// Runs the cases, prints one table per case and one summary row per scored (scheme, time); true
/// when every case's scheme reaches its digits at every scored time.
bool run_published_benchmarks(std::ostream& out,
                              const std::vector<PublishedCase>& cases = published_cases());

}  // namespace condyn
