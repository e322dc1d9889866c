#pragma once
/// Formatting shared by the report writers (compare, stress): numbers at full precision, CSV and
/// JSON string quoting, and the plotting scripts run with Debian's python3.

#include <filesystem>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace condyn {

/// A record as named text fields, in column order; empty text is a missing value.
using ReportFields = std::vector<std::pair<std::string, std::string>>;

/// 17 significant digits: a double read back is the double written.
[[nodiscard]] std::string full_precision(double v);
/// A CSV field, quoted (with doubled quotes) when it holds a comma, quote or newline.
[[nodiscard]] std::string csv_field(const std::string& s);
/// A JSON string literal with control characters escaped.
[[nodiscard]] std::string json_string(const std::string& s);

/// A CSV table: the header from the field names of `header`, then one line per record.
void write_csv_table(std::ostream& out, const ReportFields& header,
                     const std::vector<ReportFields>& records);

/// A JSON array of objects, one per record, each on its own line with `indent`: the fields named
/// in `text_fields` as strings, the others as numbers (null when empty).
void write_json_records(std::ostream& out, const std::vector<ReportFields>& records,
                        const std::set<std::string>& text_fields, const std::string& indent);

/// A plain-text table for the terminal: every column as wide as its widest cell (its header's
/// included) and kGap spaces from the next whatever its values' widths, so that no two columns
/// run together (compare's "1840405781.76" was 184040 Jacobian evaluations beside 5781.76 ms).
/// Cells are left-aligned; widths count UTF-8 characters, not bytes.
class TextTable {
 public:
  static constexpr int kGap = 2;
  /// The column names; an empty list prints no header line.
  explicit TextTable(std::vector<std::string> header, std::string indent = "");
  /// A row of cells in the header's order. A row of fewer cells (a failed run: its name and
  /// "FAILED: ...") ends in its last cell, written whole and counted in no column's width.
  void add_row(std::vector<std::string> cells);
  void print(std::ostream& out) const;

 private:
  std::vector<std::string> header_;
  std::string indent_;
  std::vector<std::vector<std::string>> rows_;
};

/// validation/SCRIPT in the source tree (the plotting scripts live there).
[[nodiscard]] std::filesystem::path validation_script(const std::string& script);

/// Runs the Python script at `path` with `args` (each quoted for /bin/sh) under Debian's python3
/// (/usr/bin/python3, else python3 on PATH), its standard output and error written to `log`
/// unless `log` is empty. Returns the script's exit code (127: no python3), -1 if it did not exit.
[[nodiscard]] int run_python_script(const std::filesystem::path& path,
                                    const std::vector<std::string>& args, const std::string& log);

/// Runs validation/SCRIPT DIR with Debian's python3 (/usr/bin/python3, else python3 on PATH),
/// its output in DIR/plots.log. Returns a one-line note: what was drawn, or why plots were skipped
/// (no python3, no matplotlib: exit 3, no script) or incomplete.
[[nodiscard]] std::string run_plot_script(const std::string& script, const std::string& dir);

}  // namespace condyn
