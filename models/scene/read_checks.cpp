// [[check]] tables (scene-format.md, "Checks for a user's own validation suite"): what a run must
// satisfy. Read here with their types, ranges and forms; the column each names is resolved against
// the built model by validation/studies/user_checks.cpp, which evaluates them.

#include <algorithm>
#include <cmath>

#include "models/core/time_roundoff.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

namespace {

/// Whether t is one of the output times 0, h, 2h, ..., t_end (SolveSpec::output_times) up to the
/// time axis' roundoff (models/core/time_roundoff.hpp, as the runs merge times); `nearest` gets the
/// output times on either side.
bool is_output_time(const SolveSpec& solve, double t, std::string& nearest) {
  const double h = solve.output_step, tol = time_merge_tolerance(0.0, solve.t_end);
  const long last = solve.output_count() - 1;  // t_end's index
  const auto time = [&](long k) { return k >= last ? solve.t_end : static_cast<double>(k) * h; };
  const double q = std::floor(t / h);
  const long k = !(q > 0.0) ? 0 : q >= static_cast<double>(last) ? last : static_cast<long>(q);
  const double below = time(k), above = time(std::min(k + 1, last));
  if (std::abs(t - below) <= tol || std::abs(t - above) <= tol) return true;
  nearest = TomlAccess::fmt(below) + " and " + TomlAccess::fmt(above);
  return false;
}

}  // namespace

void SceneReader::read_checks(const toml::node& node, const SolveSpec& solve,
                              std::vector<CheckSpec>& out) const {
  const auto& arr = array(node, "check");
  if (arr.empty()) fail(node, "check", "is empty: give [[check]] tables or omit them");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string path = index("check", i);
    const auto& t = table(*arr.get(i), path);
    check_keys(t, path, {"quantity", "at", "value", "tolerance", "max_abs", "reference"});
    CheckSpec c;
    c.where = at(*arr.get(i), path);
    c.quantity = string(required(t, path, "quantity"), join(path, "quantity"));
    if (c.quantity.empty()) fail(*t.get("quantity"), join(path, "quantity"), "must not be empty");
    const bool has_at = t.contains("at"), has_max = t.contains("max_abs"),
               has_ref = t.contains("reference");
    if (static_cast<int>(has_at) + static_cast<int>(has_max) + static_cast<int>(has_ref) != 1) {
      fail(*arr.get(i), path,
           "give exactly one of: at (with value and tolerance), max_abs, or reference (with "
           "tolerance)");
    }
    const auto bound = [&](const char* key) {
      const std::string p = join(path, key);
      const double v = number(required(t, path, key), p);
      if (v < 0.0) fail(*t.get(key), p, "must be >= 0");
      return v + 0.0;  // -0.0 is 0, printed as 0 ("bound -0" read as negative)
    };
    if (has_max) {
      for (const char* key : {"value", "tolerance"}) {
        if (t.contains(key)) {
          fail(*t.get(key), join(path, key),
               "does not go with max_abs (max_abs is itself the bound on |quantity|)");
        }
      }
      c.form = CheckSpec::Form::max_abs;
      c.bound = bound("max_abs");
    } else if (has_at) {
      c.form = CheckSpec::Form::at_value;
      const std::string p = join(path, "at");
      c.at = number(*t.get("at"), p) + 0.0;  // -0.0 is t = 0, not printed 't = -0
      std::string nearest;
      if (c.at < 0.0 || c.at > solve.t_end * (1.0 + 1e-12)) {
        fail(*t.get("at"), p, "is outside the run, [0, " + fmt(solve.t_end) + "]");
      }
      if (!is_output_time(solve, c.at, nearest)) {
        fail(*t.get("at"), p,
             "is not an output time (multiples of output_step " + fmt(solve.output_step) +
                 " and t_end; the nearest are " + nearest + ")");
      }
      c.value = number(required(t, path, "value"), join(path, "value"));
      c.tolerance = bound("tolerance");
    } else {
      if (t.contains("value")) {
        fail(*t.get("value"), join(path, "value"),
             "does not go with reference (the file holds it)");
      }
      c.form = CheckSpec::Form::reference;
      const std::string p = join(path, "reference");
      const auto& ref = table(*t.get("reference"), p);
      check_keys(ref, p, {"file"});
      // One row is a reference too: the run is compared at its times.
      c.reference = table_file(required(ref, p, "file"), join(p, "file"), c.quantity, 1);
      // The contract's reference has `t` and the quantity's column: a first column headed
      // otherwise (a row number) would be read as the times.
      if (c.reference->time_column != "t") {
        fail(*ref.get("file"), join(p, "file"),
             c.reference->file + ": its first column is headed '" + c.reference->time_column +
                 "': a reference's first column is the time, headed t (as in t," + c.quantity +
                 ")");
      }
      const auto& times = c.reference->times;
      if (times.front() < -1e-12 * solve.t_end || times.back() > solve.t_end * (1.0 + 1e-12)) {
        fail(*ref.get("file"), join(p, "file"),
             c.reference->file + ": its times run from " + fmt(times.front()) + " to " +
                 fmt(times.back()) + ", outside the run [0, " + fmt(solve.t_end) + "]");
      }
      c.tolerance = bound("tolerance");
    }
    out.push_back(std::move(c));
  }
}

}  // namespace condyn
