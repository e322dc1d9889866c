#pragma once
/// A number written in a data file (a Matrix Market entry, a table's cell): what is wrong with
/// it, if anything, the shortest text of a double, and a cell as a message shows it. Shared by
/// models/scene/matrix_market.cpp, models/core/time_table.cpp and
/// validation/studies/user_checks.cpp.

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>

namespace condyn {

enum class NumberCell { ok, not_a_number, out_of_range };

/// Parses `text` whole (a leading '+' allowed, as C's strtod and SciPy's readers take it) into
/// `out`. out_of_range: a number whose magnitude is beyond the double range (1e400) or below its
/// smallest subnormal (1e-400), which from_chars refuses rather than round to inf or 0.
inline NumberCell parse_number_cell(std::string_view text, double& out) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  if (first == last) return NumberCell::not_a_number;
  const auto [end, ec] = std::from_chars(first, last, out);
  if (end != last) return NumberCell::not_a_number;
  if (ec == std::errc::result_out_of_range) return NumberCell::out_of_range;
  return ec == std::errc() ? NumberCell::ok : NumberCell::not_a_number;
}

/// "is not a number" or "is out of the double range (beyond about 1.8e308, or below 4.9e-324
/// but not 0)" for a cell parse_number_cell refused.
inline const char* number_cell_problem(NumberCell kind) {
  return kind == NumberCell::out_of_range
             ? "is out of the double range (beyond about 1.8e308, or nonzero below 4.9e-324)"
             : "is not a number";
}

/// The shortest text that reads back as v (0.1, not 0.10000000000000001): a number in a message
/// shown exactly, so that it is never rounded onto the figure it is compared with.
inline std::string shortest_number(double v) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return ec == std::errc() ? std::string(buffer.data(), end) : std::to_string(v);
}

/// A cell or token as a message quotes it: control bytes as '?' (a NUL cut the message off, an
/// escape sequence reached the terminal), at most 40 characters.
inline std::string shown_cell(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string out(s.substr(0, kMax));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return s.size() > kMax ? out + "..." : out;
}

}  // namespace condyn
