#pragma once
/// Tabulated time functions (scene-format.md, "Time functions from data"): samples (t_k, v_k) read
/// from a CSV file, t strictly increasing, at least two samples, all finite. The function is
///
///   f(t) = v_0 for t <= t_0,   f(t) = v_last for t >= t_last,
///   f(t) = v_k + (v_{k+1} − v_k) (t − t_k) / (t_{k+1} − t_k) on [t_k, t_{k+1}],
///
/// evaluated by binary search, O(log n). Its first derivative is the slope of the segment that
/// holds t (right-continuous: at a sample, the slope of the segment that starts there; 0 outside
/// [t_0, t_last)); its second derivative is 0 (the impulses at the samples are not represented).

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace condyn {

/// A malformed table file: `line` is the file's 1-based line (0 when the whole file is at fault,
/// e.g. it cannot be opened or holds too few samples); what() says what is wrong.
class TimeTableError : public std::runtime_error {
 public:
  TimeTableError(int line, const std::string& what) : std::runtime_error(what), line_(line) {}
  [[nodiscard]] int line() const { return line_; }

 private:
  int line_;
};

/// The samples of one column, immutable once read (shared by every copy of the time function).
struct TimeTable {
  std::string file;         ///< the file as the scene names it (for describe())
  std::string column;       ///< the values' column: its header name, or "column 2" without a header
  std::string time_column;  ///< the time column's header name; empty without a header
  std::vector<double> times, values;
  std::vector<int> lines;      ///< the file's 1-based line of each sample (for messages)
  double max_abs_value = 0.0;  ///< max |v_k|
  double max_abs_slope = 0.0;  ///< max |(v_{k+1} − v_k) / (t_{k+1} − t_k)| (may be inf)

  [[nodiscard]] std::size_t samples() const { return times.size(); }
  /// f(t), piecewise linear, held constant outside [t_0, t_last].
  [[nodiscard]] double value(double t) const;
  /// f'(t): the slope of the segment [t_k, t_{k+1}) holding t; 0 outside [t_0, t_last).
  [[nodiscard]] double slope(double t) const;
  /// f'(t) as an integration segment that began at `reference` < t sees it: the slope of the
  /// segment holding `reference` up to and at that segment's end t_{k+1} (within kTimeMergeUlps
  /// of it: a step that lands on a sample is on the side it comes from, the one-sided
  /// derivative), slope(t) beyond it or when reference >= t.
  [[nodiscard]] double slope(double t, double reference) const;
};

/// Parses CSV text: `#` lines and blank lines are skipped; the first other line is a header of
/// column names when its first cell is not a number; the first column is time; `column` names the
/// values' column (empty: the second column). Only the time and value cells are read as numbers.
/// Throws TimeTableError naming the line of the first problem: an unknown column (or a column
/// asked of a file without header), a row too short, a cell that is not a number or not finite,
/// a time not after the previous one, fewer than `min_samples` samples (2 for a time function,
/// which interpolates; 1 for a check's reference, compared at its own times).
[[nodiscard]] TimeTable parse_time_table(const std::string& text, const std::string& column,
                                         std::size_t min_samples = 2);
/// The same, from a file (regular files only); `file` of the result is left to the caller.
[[nodiscard]] TimeTable read_time_table(const std::string& path, const std::string& column,
                                        std::size_t min_samples = 2);

}  // namespace condyn
