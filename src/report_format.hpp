#pragma once
/// Formatting shared by the report writers (compare, stress): numbers at full precision, CSV and
/// JSON string quoting, and the plotting scripts run with Debian's python3.

#include <string>

namespace condyn {

/// 17 significant digits: a double read back is the double written.
[[nodiscard]] std::string full_precision(double v);
/// A CSV field, quoted (with doubled quotes) when it holds a comma, quote or newline.
[[nodiscard]] std::string csv_field(const std::string& s);
/// A JSON string literal with control characters escaped.
[[nodiscard]] std::string json_string(const std::string& s);

/// Runs validation/SCRIPT DIR with Debian's python3 (/usr/bin/python3, else python3 on PATH),
/// its output in DIR/plots.log. Returns a one-line note: what was drawn, or why plots were skipped
/// (no python3, no matplotlib: exit 3, no script) or incomplete.
[[nodiscard]] std::string run_plot_script(const std::string& script, const std::string& dir);

}  // namespace condyn
