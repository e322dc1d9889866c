#pragma once
/// A recorded support displacement with the two time derivatives a prescribed displacement needs
/// (docs/scenes.md, "Support motion"). The record holds samples (t_k, d_k, v_k, a_k): the
/// displacement, velocity and acceleration at each sample time. On [t_k, t_{k+1}] the function is
/// the quintic Hermite polynomial that takes d, v and a at both ends, so it is twice continuously
/// differentiable and its first and second derivatives are its own (a constraint's ġ and g̈ are
/// exact derivatives of its g, whatever the records hold between samples). Outside
/// [t_0, t_last] it holds d_0 before and d_last after, with zero velocity and acceleration (the
/// end samples themselves keep their recorded velocity and acceleration).
///
/// The samples come either from a record triple (three columns read as given) or from an
/// acceleration record alone, piecewise linear, integrated twice from rest exactly (each piece of
/// the displacement a cubic, which the quintic reproduces), after an optional baseline correction.

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "models/core/time_table.hpp"

namespace condyn {

/// How an integrated acceleration record is corrected before its second integration.
enum class Baseline {
  none,   ///< integrated as recorded: the displacement may drift away at the end
  linear  ///< a(t) − (c0 + c1 (t − t_0)), c0 and c1 such that v and d are 0 at the last sample
};

/// A record whose parts do not fit together (different sample times): `part` is "velocity" or
/// "acceleration", `line` the 1-based line of the offending sample in `file` (that part's file),
/// what() says what is wrong.
class RecordMismatch : public std::runtime_error {
 public:
  RecordMismatch(std::string part, std::string file, int line, const std::string& what)
      : std::runtime_error(what), part_(std::move(part)), file_(std::move(file)), line_(line) {}
  [[nodiscard]] const std::string& part() const { return part_; }
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] int line() const { return line_; }

 private:
  std::string part_, file_;
  int line_;
};

struct KinematicRecord {
  std::string source;  ///< what it was made from, e.g. "left.csv:d,v,a" (for describe())
  std::vector<double> times, displacement, velocity, acceleration;
  /// bound[order]: an upper bound of |d^order/dt^order f| over every piece (from the pieces'
  /// polynomial coefficients), for the overflow checks; 0 for all three means f is constant 0.
  std::array<double, 3> bound{};

  [[nodiscard]] std::size_t samples() const { return times.size(); }
  /// d^order/dt^order of the interpolant at t, order in {0, 1, 2}.
  [[nodiscard]] double derivative(int order, double t) const;
};

/// The samples of three tables of one support (displacement, velocity, acceleration, each
/// already scaled to the scene's units). Throws RecordMismatch when the velocity's or the
/// acceleration's sample times differ from the displacement's (naming the first that differs).
[[nodiscard]] KinematicRecord record_from_triple(const TimeTable& displacement,
                                                 const TimeTable& velocity,
                                                 const TimeTable& acceleration,
                                                 const std::string& source);

/// The samples of an acceleration table (piecewise linear, already scaled) integrated twice from
/// d = v = 0 at its first sample, after the baseline correction.
[[nodiscard]] KinematicRecord record_from_acceleration(const TimeTable& acceleration,
                                                       Baseline baseline,
                                                       const std::string& source);

}  // namespace condyn
