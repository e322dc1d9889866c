#include "src/reports/report_format.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace condyn {

std::string full_precision(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void write_csv_table(std::ostream& out, const ReportFields& header,
                     const std::vector<ReportFields>& records) {
  const auto line = [&](const ReportFields& fields, bool names) {
    bool first = true;
    for (const auto& [key, value] : fields) {
      out << (first ? "" : ",") << (names ? key : csv_field(value));
      first = false;
    }
    out << "\n";
  };
  line(header, true);
  for (const auto& r : records) line(r, false);
}

void write_json_records(std::ostream& out, const std::vector<ReportFields>& records,
                        const std::set<std::string>& text_fields, const std::string& indent) {
  for (std::size_t k = 0; k < records.size(); ++k) {
    out << indent << "{";
    bool first = true;
    for (const auto& [key, value] : records[k]) {
      out << (first ? "" : ", ") << json_string(key) << ": ";
      if (text_fields.count(key) > 0) {
        out << json_string(value);
      } else {
        out << (value.empty() ? "null" : value);
      }
      first = false;
    }
    out << "}" << (k + 1 < records.size() ? "," : "") << "\n";
  }
}

namespace {

/// Characters of UTF-8 text: its bytes that do not continue a character.
std::size_t display_width(const std::string& s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

}  // namespace

TextTable::TextTable(std::vector<std::string> header, std::string indent)
    : header_(std::move(header)), indent_(std::move(indent)) {}

void TextTable::add_row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }

void TextTable::print(std::ostream& out) const {
  std::size_t columns = header_.size();
  for (const auto& r : rows_) columns = std::max(columns, r.size());
  std::vector<std::size_t> width(columns, 0);
  const auto measure = [&](const std::vector<std::string>& cells, bool whole) {
    // A short row's last cell spans the columns after it: it sets no width.
    const std::size_t counted = whole ? cells.size() : cells.size() - 1;
    for (std::size_t c = 0; c < counted; ++c)
      width[c] = std::max(width[c], display_width(cells[c]));
  };
  if (!header_.empty()) measure(header_, true);
  for (const auto& r : rows_) {
    if (!r.empty()) measure(r, r.size() == columns);
  }
  const auto line = [&](const std::vector<std::string>& cells) {
    std::string text = indent_;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      text += cells[c];
      if (c + 1 < cells.size()) {
        text += std::string(width[c] - std::min(width[c], display_width(cells[c])) + kGap, ' ');
      }
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out << text << "\n";
  };
  if (!header_.empty()) line(header_);
  for (const auto& r : rows_) line(r);
}

namespace {

/// `s` as one word for /bin/sh: in single quotes, each ' written as '\''.
std::string shell_word(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::filesystem::path validation_script(const std::string& script) {
  return std::filesystem::path(CONDYN_SOURCE_DIR) / "validation" / script;
}

int run_python_script(const std::filesystem::path& path, const std::vector<std::string>& args,
                      const std::string& log) {
  const std::string python =
      std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  std::string cmd = shell_word(python) + " " + shell_word(path.string());
  for (const auto& a : args) cmd += " " + shell_word(a);
  if (!log.empty()) cmd += " > " + shell_word(log) + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string run_plot_script(const std::string& script, const std::string& dir) {
  const std::filesystem::path path = validation_script(script);
  if (!std::filesystem::exists(path)) return "plots skipped: " + path.string() + " not found";
  const int code = run_python_script(path, {dir}, dir + "/plots.log");
  switch (code) {
    case 0:
      return "plots written to " + dir + " (PNG, and PDF or SVG)";
    case 3:
      return "plots skipped: matplotlib is not installed (apt-get install python3-matplotlib)";
    case 127:
      return "plots skipped: python3 is not installed";
    default:
      return "plots incomplete: the plotting script exited with " + std::to_string(code) +
             " (see " + dir + "/plots.log)";
  }
}

}  // namespace condyn
