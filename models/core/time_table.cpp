#include "models/core/time_table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <utility>

#include "models/core/line_reader.hpp"
#include "models/core/number_cell.hpp"
#include "models/core/time_roundoff.hpp"

namespace condyn {

namespace {

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return std::string(s.substr(first, last - first + 1));
}

/// The cells of a line, trimmed. A cell may be in double quotes, as R's write.csv writes names
/// (RFC 4180): a comma inside is part of it, "" stands for one quote, the quotes go.
std::vector<std::string> cells(const std::string& line, int line_no) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string cell;
    if (i < line.size() && line[i] == '"') {
      ++i;
      while (true) {
        if (i >= line.size()) {
          throw TimeTableError(line_no, "a double quote opens a cell and none closes it");
        }
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cell += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        cell += line[i++];
      }
      const auto comma = line.find(',', i);
      if (!trim(std::string_view(line).substr(
                    i, comma == std::string::npos ? std::string::npos : comma - i))
               .empty()) {
        throw TimeTableError(line_no, "text follows the closing double quote of a cell");
      }
      out.push_back(cell);
      if (comma == std::string::npos) return out;
      i = comma + 1;
      continue;
    }
    const auto comma = line.find(',', i);
    out.push_back(trim(std::string_view(line).substr(
        i, comma == std::string::npos ? std::string::npos : comma - i)));
    if (comma == std::string::npos) return out;
    i = comma + 1;
  }
}

/// For a row read as one cell: the separator it seems to use instead of commas, said with what to
/// do, or "" when it holds none. Spreadsheets write CSV with semicolons where the decimal mark is
/// a comma, and tab-separated text when asked for text.
std::string other_separator(const std::string& row) {
  if (row.find(';') != std::string::npos) {
    return "; its cells seem separated by semicolons (';'), as spreadsheets write CSV where the "
           "decimal mark is a comma: condyn reads comma-separated values with a decimal point "
           "(export with ',' between cells and '.' in numbers)";
  }
  if (row.find('\t') != std::string::npos) {
    return "; its cells seem separated by tabs: condyn reads comma-separated values (save the "
           "table as CSV, ',' between cells)";
  }
  if (row.find(' ') != std::string::npos) {
    return "; its cells seem separated by spaces: condyn reads comma-separated values (',' "
           "between cells)";
  }
  return "";
}

/// The whole cell as a double (a leading '+' allowed), or false.
bool parse_number(const std::string& cell, double& out) {
  return parse_number_cell(cell, out) == NumberCell::ok;
}

}  // namespace

double TimeTable::value(double t) const {
  if (t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  // The segment [t_k, t_{k+1}) holding t: t_k is the last time <= t.
  const auto k =
      static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin() - 1);
  const double w = (t - times[k]) / (times[k + 1] - times[k]);
  return values[k] + w * (values[k + 1] - values[k]);
}

double TimeTable::slope(double t) const {
  if (t < times.front() || t >= times.back()) return 0.0;
  const auto k =
      static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin() - 1);
  return (values[k + 1] - values[k]) / (times[k + 1] - times[k]);
}

double TimeTable::slope(double t, double reference) const {
  if (!(reference < t) || reference >= times.back()) return slope(t);
  // The first sample after `reference`: the end of its segment (of the constant before t_0 when
  // it is t_0).
  const auto next = static_cast<std::size_t>(
      std::upper_bound(times.begin(), times.end(), reference) - times.begin());
  if (t > times[next] + time_merge_tolerance(0.0, times[next])) return slope(t);
  return next == 0 ? 0.0 : (values[next] - values[next - 1]) / (times[next] - times[next - 1]);
}

namespace {

/// What the first row fixes for the rows after it.
struct TableLayout {
  std::size_t value_col = 1;  ///< the values' column (0-based)
  // The first row's cells (the header's, else the first sample's) and its line: every sample
  // has as many. A longer row is a shifted one as often as a short one is (a decimal comma,
  // 0,5 for 0.5, splits a value in two), and its cells would be read from the wrong columns.
  std::size_t width = 0;
  int width_line = 0;
};

/// A header row: the time column (first, and not a row index) and the values' column (`column`,
/// or the second when empty), named in `table`; returns the values' column.
std::size_t read_header_row(const std::vector<std::string>& row, int line_no,
                            const std::string& column, TimeTable& table) {
  table.time_column = row.front();
  // R's write.csv and pandas' to_csv put a row index first by default: an unnamed first
  // column, or a later one named as time is. Read as time, it stretches the record.
  const auto named_time = [](std::string name) {
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return name == "t" || name == "time";
  };
  const auto later_time = std::find_if(row.begin() + 1, row.end(), named_time);
  if (trim(row.front()).empty() || (!named_time(row.front()) && later_time != row.end())) {
    throw TimeTableError(
        line_no, "the first column holds the time, but it is " +
                     (trim(row.front()).empty() ? std::string("unnamed")
                                                : "'" + shown_cell(row.front()) + "'") +
                     (later_time != row.end()
                          ? " and column " + std::to_string(later_time - row.begin() + 1) +
                                " is '" + shown_cell(*later_time) + "'"
                          : std::string()) +
                     ": a row index, as R's write.csv and pandas' to_csv write by default? Write "
                     "the table without it (write.csv(..., row.names = FALSE), "
                     "to_csv(..., index = False)) or with time first");
  }
  if (column.empty()) {
    table.column = row[1];
    return 1;
  }
  const auto it = std::find(row.begin() + 1, row.end(), column);
  if (it == row.end()) {
    std::string names;
    for (std::size_t c = 1; c < row.size(); ++c) names += (c > 1 ? ", " : "") + shown_cell(row[c]);
    throw TimeTableError(line_no,
                         "no column '" + column + "' (the value columns are: " + names + ")");
  }
  if (std::find(it + 1, row.end(), column) != row.end()) {
    throw TimeTableError(line_no, "two columns are named '" + column +
                                      "': rename one (which is meant is not clear)");
  }
  table.column = column;
  return static_cast<std::size_t>(it - row.begin());
}

/// The first row (`trimmed` its text): its width, and whether it is a header (its first cell not
/// a number), read by read_header_row; else the values are in column 2.
bool read_first_row(const std::vector<std::string>& row, const std::string& trimmed, int line_no,
                    const std::string& column, TimeTable& table, TableLayout& layout) {
  layout.width = row.size();
  layout.width_line = line_no;
  double ignored = 0.0;
  const bool header = !parse_number(row.front(), ignored);
  if (row.size() < 2) {
    throw TimeTableError(line_no, "has " + std::to_string(row.size()) +
                                      " column: a table needs time and a column of values" +
                                      other_separator(trimmed));
  }
  if (header) {
    layout.value_col = read_header_row(row, line_no, column, table);
    return true;
  }
  if (!column.empty()) {
    // A check's reference names its column by the check's quantity, a time function by
    // `column`: the remedy that serves both is the header.
    throw TimeTableError(line_no, "has no header line naming its columns, so no column '" + column +
                                      "' (add a header line such as t," + column + ")");
  }
  table.column = "column 2";
  return false;
}

/// A sample row's time and value: as many cells as the first row, both numbers and finite.
std::pair<double, double> read_sample(const std::vector<std::string>& row,
                                      const std::string& trimmed, int line_no,
                                      const TableLayout& layout) {
  if (row.size() <= layout.value_col) {
    throw TimeTableError(line_no, "has " + std::to_string(row.size()) +
                                      " cell(s) but the values are in column " +
                                      std::to_string(layout.value_col + 1) +
                                      (row.size() == 1 ? other_separator(trimmed) : ""));
  }
  if (row.size() != layout.width) {
    throw TimeTableError(line_no, "has " + std::to_string(row.size()) + " cells, line " +
                                      std::to_string(layout.width_line) + " has " +
                                      std::to_string(layout.width) +
                                      ": every row needs one cell per column (a decimal "
                                      "comma, as in 0,5, splits a value in two)");
  }
  double t = 0.0, v = 0.0;
  for (const auto& [cell, out, what] :
       {std::tuple{row[0], &t, "time"}, std::tuple{row[layout.value_col], &v, "value"}}) {
    if (const NumberCell kind = parse_number_cell(cell, *out); kind != NumberCell::ok) {
      throw TimeTableError(line_no, std::string("the ") + what + " '" + shown_cell(cell) + "' " +
                                        number_cell_problem(kind));
    }
    if (!std::isfinite(*out)) {
      throw TimeTableError(
          line_no, std::string("the ") + what + " '" + shown_cell(cell) + "' is not finite");
    }
  }
  return {t, v};
}

/// Appends the sample (t, v) after the previous one, whose time it must follow.
void add_sample(TimeTable& table, double t, double v, int line_no) {
  if (!table.times.empty() && !(t > table.times.back())) {
    throw TimeTableError(
        line_no, "the time " + shortest_number(t) + " is not after the previous sample's " +
                     shortest_number(table.times.back()) + " (times must increase strictly)");
  }
  if (!table.times.empty() && !std::isfinite(t - table.times.back())) {
    // −1e308 then 1e308: the interval overflows, and interpolation across it gave the first
    // value where the line between the samples is meant.
    throw TimeTableError(line_no, "the time " + shortest_number(t) +
                                      " is too far from the previous sample's " +
                                      shortest_number(table.times.back()) +
                                      ": their interval overflows the double range");
  }
  if (!table.times.empty()) {
    const double slope = (v - table.values.back()) / (t - table.times.back());
    table.max_abs_slope = std::max(table.max_abs_slope, std::abs(slope));
  }
  table.times.push_back(t);
  table.values.push_back(v);
  table.lines.push_back(line_no);
  table.max_abs_value = std::max(table.max_abs_value, std::abs(v));
}

}  // namespace

TimeTable parse_time_table(const std::string& text, const std::string& column,
                           std::size_t min_samples) {
  TimeTable table;
  std::istringstream in(text);
  LineReader lines(in);  // LF, CRLF or CR endings; a byte order mark is no part of the first cell
  std::string_view line;
  bool first_row = true;
  TableLayout layout;
  while (lines.next(line)) {
    const int line_no = lines.line_number();
    const std::string trimmed = trim(line);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    const auto row = cells(trimmed, line_no);
    if (first_row) {
      first_row = false;
      if (read_first_row(row, trimmed, line_no, column, table, layout)) continue;
    }
    const auto [t, v] = read_sample(row, trimmed, line_no, layout);
    add_sample(table, t, v, line_no);
  }
  if (table.times.size() < min_samples) {
    throw TimeTableError(0, "has " + std::to_string(table.times.size()) +
                                " sample(s): a table needs at least " +
                                std::to_string(min_samples));
  }
  return table;
}

TimeTable read_time_table(const std::string& path, const std::string& column,
                          std::size_t min_samples) {
  // A device or a pipe would be read forever or block: regular files only.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw TimeTableError(0, "is not a regular file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TimeTableError(0, "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw TimeTableError(0, "cannot read the file");
  return parse_time_table(text.str(), column, min_samples);
}

}  // namespace condyn
