#pragma once
/// Report lines wrapped for a terminal: `info`'s "label: text" and "label: a, b, c" lines.

#include <cstddef>
#include <string>
#include <vector>

namespace condyn {

/// Lines of a report stay within this width (a terminal, a log viewer, a diff).
inline constexpr std::size_t kReportWidth = 100;
/// Long lists (hundreds of masters) are shown in full up to this many lines, then counted.
inline constexpr std::size_t kMaxListLines = 8;

/// "label: text" with the words of text wrapped at kReportWidth columns, continuation lines
/// indented by the label's width; ends in a newline. Text of several lines is printed as it is.
[[nodiscard]] std::string wrapped_text(const std::string& label, const std::string& text);

/// "label: a, b, c" wrapped at kReportWidth columns, continuation lines indented by the label's
/// width; beyond kMaxListLines lines the rest is counted ("... and 290 more (598 in all)");
/// "label: none" for an empty list.
[[nodiscard]] std::string wrapped_list(const std::string& label,
                                       const std::vector<std::string>& names);

}  // namespace condyn
