// Report lines wrapped for a terminal (src/reports/wrapped_lines.hpp).

#include "src/reports/wrapped_lines.hpp"

#include <sstream>

namespace condyn {

std::string wrapped_text(const std::string& label, const std::string& text) {
  if (text.find('\n') != std::string::npos) return label + text + "\n";
  const std::string indent(label.size(), ' ');
  std::string out = label, word;
  std::size_t width = label.size();
  std::istringstream words(text);
  bool first = true;
  while (words >> word) {
    if (!first && width + 1 + word.size() > kReportWidth) {
      out += "\n" + indent;
      width = indent.size();
      first = true;
    }
    out += (first ? "" : " ") + word;
    width += (first ? 0 : 1) + word.size();
    first = false;
  }
  return out + "\n";
}

std::string wrapped_list(const std::string& label, const std::vector<std::string>& names) {
  if (names.empty()) return label + "none\n";
  const std::string indent(label.size(), ' ');
  std::vector<std::vector<std::string>> lines(1);
  std::size_t width = label.size();
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string item = names[k] + (k + 1 < names.size() ? "," : "");
    if (!lines.back().empty() && width + 1 + item.size() > kReportWidth) {
      lines.emplace_back();
      width = indent.size();
    }
    width += (lines.back().empty() ? 0 : 1) + item.size();
    lines.back().push_back(item);
  }
  std::string suffix;
  if (lines.size() > kMaxListLines) {
    lines.resize(kMaxListLines);
    auto& last = lines.back();
    std::size_t shown = 0;
    for (const auto& l : lines) shown += l.size();
    const auto line_width = [&last, &indent] {
      std::size_t w = indent.size();
      for (const auto& item : last) w += item.size() + 1;
      return w;
    };
    do {
      suffix = "... and " + std::to_string(names.size() - shown) + " more (" +
               std::to_string(names.size()) + " in all)";
      if (line_width() + suffix.size() <= kReportWidth || last.size() <= 1) break;
      last.pop_back();
      --shown;
    } while (true);
  }
  std::string out;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    std::string line = l == 0 ? label : indent;
    for (std::size_t k = 0; k < lines[l].size(); ++k) line += (k ? " " : "") + lines[l][k];
    if (l + 1 == lines.size() && !suffix.empty()) line += " " + suffix;
    out += line + "\n";
  }
  return out;
}

}  // namespace condyn
