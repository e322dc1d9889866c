// Ground motion records: their peaks and the unit their names state
// (models/assembly/ground_records.hpp), reported by the builder stage below.

#include "models/assembly/ground_records.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "models/assembly/model_builder.hpp"

namespace condyn {

RecordPeak record_peak(const TimeTerm& table_term, double t_end) {
  RecordPeak peak{table_term.value(0.0), 0.0};
  const auto consider = [&](double t) {
    const double v = table_term.value(t);
    if (std::abs(v) > std::abs(peak.value)) peak = {v, t};
  };
  for (const double t : table_term.table->times) {
    if (t > 0.0 && t < t_end) consider(t);
  }
  consider(t_end);
  return peak;
}

bool name_says_g(const std::string& name) {
  const auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; };
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name[i] != 'g' && name[i] != 'G') continue;
    const bool starts = i == 0 || !word(name[i - 1]);
    const bool ends = i + 1 == name.size() || !word(name[i + 1]);
    if (starts && ends) return true;
  }
  return false;
}

bool scale_is_g(double scale, bool si) {
  // g in m, cm, mm, ft and in per s² (ft: 9.80665 / 0.3048, in: 9.80665 / 0.0254).
  constexpr std::array<double, 5> kG = {kStandardGravity, 100.0 * kStandardGravity,
                                        1000.0 * kStandardGravity, kStandardGravity / 0.3048,
                                        kStandardGravity / 0.0254};
  const auto near = [scale](double g) { return std::abs(scale - g) <= kScaleNearG * g; };
  return si ? near(kStandardGravity) : std::any_of(kG.begin(), kG.end(), near);
}

namespace {

/// Three significant digits: a peak to read, not to reuse.
std::string digits3(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

}  // namespace

/// One summary line per table of the ground's acceleration (its peak over the run, in g too when
/// the scene is SI), and the warnings of models/assembly/ground_records.hpp: a name that says g
/// beside a scale that is not g, an SI peak beyond kMaxPlausiblePeakG.
void ModelBuilder::report_ground_records(const TimeFunction& acceleration) {
  const bool si = spec_.si_units;
  const double t_end = spec_.solve.t_end;
  for (const auto& term : acceleration.terms()) {
    if (term.kind != TimeTerm::Kind::table || !term.table) continue;
    const TimeTable& table = *term.table;
    const RecordPeak peak = record_peak(term, t_end);
    const double peak_g = std::abs(peak.value) / kStandardGravity;
    std::string line = term.describe() + ": peak " + digits3(std::abs(peak.value));
    line += si ? " m/s^2 (" + digits3(peak_g) + " g) at t = " + fmt(peak.t) + " s"
               : " at t = " + fmt(peak.t) + " (the scene's units; units = \"SI\" adds g)";
    report_.ground_records.push_back(line);
    const std::string key = "ground_motion.acceleration: ";
    const std::string stem = std::filesystem::path(table.file).stem().string();
    const bool says_g = name_says_g(table.column) || name_says_g(stem);
    if (says_g && !scale_is_g(term.amplitude, si)) {
      const std::string named = "'" + (name_says_g(table.column) ? table.column : table.file) + "'";
      report_.warnings.push_back(
          key + named + " says the record " + table.file + " is in g, but its scale " +
          fmt(term.amplitude) + " is not g " +
          (si ? "in m/s^2 (" + fmt(kStandardGravity) + ", the scene being SI): the record acts " +
                    digits3(term.amplitude / kStandardGravity) +
                    " times as large as its values in g; give scale = 9.81"
              : std::string("in m, cm, mm, ft or in per s^2 (9.81, 981, 9810, 32.2, 386)") +
                    ": give scale = g in the scene's units (9.81 in metres)"));
    }
    if (si && peak_g > kMaxPlausiblePeakG) {
      report_.warnings.push_back(
          key + term.describe() + " peaks at " + digits3(std::abs(peak.value)) + " m/s^2 (" +
          digits3(peak_g) + " g) at t = " + fmt(peak.t) + " s, beyond " +
          digits3(kMaxPlausiblePeakG) +
          " g (recorded ground motions stay below about 4 g): check the record's unit and "
          "scale");
    }
  }
}

}  // namespace condyn
