#include "src/cli/cli_flags.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "models/scene/scene_parser.hpp"

namespace condyn {

namespace {

std::string shortest(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// The message for a value that is not a number: what was given, what is expected.
std::string not_a_number(const std::string& text) {
  return "'" + text + "' is not a decimal number within the double range (write e.g. 1e-6 or 0.5)";
}

}  // namespace

std::optional<double> parse_decimal(const std::string& text) {
  // [+-] digits [. digits] [(e|E) [+-] digits], at least one digit in the mantissa.
  std::size_t i = 0;
  const std::size_t n = text.size();
  const auto digits = [&]() {
    const std::size_t start = i;
    while (i < n && text[i] >= '0' && text[i] <= '9') ++i;
    return i - start;
  };
  if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < n && text[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return std::nullopt;
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return std::nullopt;
  }
  if (i != n) return std::nullopt;
  // Beyond the double range: no value. Below it (1e-320, subnormal or 0) the number is kept,
  // and the flag's range names what is wrong with it.
  const double v = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(v)) return std::nullopt;
  return v;
}

double parse_rtol_flag(const std::string& flag, const std::string& text) {
  const auto v = parse_decimal(text);
  if (!v) throw CLI::ValidationError(flag, not_a_number(text));
  if (!(*v >= kMinRtol && *v < 1.0)) {
    throw CLI::ValidationError(flag, text + " is out of range: a relative tolerance lies in [" +
                                         shortest(kMinRtol) + ", 1)");
  }
  return *v;
}

CLI::Validator rtol_check() {
  return {[](std::string& text) {
            const auto v = parse_decimal(text);
            if (!v) return not_a_number(text);
            if (!(*v >= kMinRtol && *v < 1.0)) {
              return text + " is out of range: a relative tolerance lies in [" +
                     shortest(kMinRtol) + ", 1)";
            }
            return std::string();
          },
          "RTOL in [" + shortest(kMinRtol) + ", 1)"};
}

CLI::Validator atol_check() {
  return {[](std::string& text) {
            const auto v = parse_decimal(text);
            if (!v) return not_a_number(text);
            if (!(*v >= kMinAtol)) {
              return text + " is out of range: an absolute tolerance is at least " +
                     shortest(kMinAtol) + " (smaller error weights overflow)";
            }
            return std::string();
          },
          "ATOL >= " + shortest(kMinAtol)};
}

CLI::Validator positive_check() {
  return {[](std::string& text) {
            const auto v = parse_decimal(text);
            if (!v) return not_a_number(text);
            if (!(*v > 0.0)) return text + " must be > 0";
            return std::string();
          },
          "NUMBER > 0"};
}

namespace {

/// A value that is a flag (`--out --scheme ggl`: --out took '--scheme' and ggl was left over):
/// the value is missing. A file so named can be given as ./--name.
std::string flag_as_value(const std::string& text, bool file) {
  if (text.size() > 2 && text.compare(0, 2, "--") == 0) {
    return "a value is missing ('" + text + "' is a flag" +
           (file ? "; a file named so is ./" + text : std::string()) + ")";
  }
  return {};
}

}  // namespace

bool is_blank(const std::string& text) {
  return text.find_first_not_of(" \t\n\r\v\f") == std::string::npos;
}

CLI::Validator file_name_check() {
  return {[](std::string& text) {
            if (is_blank(text)) {
              return std::string("an empty name: name a file (or - for standard output)");
            }
            return flag_as_value(text, true);
          },
          "FILE"};
}

CLI::Validator non_empty_check() {
  return {[](std::string& text) {
            if (is_blank(text)) {
              return std::string("is empty (leave the flag out instead)");
            }
            return flag_as_value(text, false);
          },
          "TEXT"};
}

CLI::Validator decimal_range_check(double lo, double hi) {
  return {[lo, hi](std::string& text) {
            const auto v = parse_decimal(text);
            if (!v) return not_a_number(text);
            if (!(*v >= lo && *v <= hi)) {
              return text + " is out of range [" + shortest(lo) + ", " + shortest(hi) + "]";
            }
            return std::string();
          },
          "NUMBER in [" + shortest(lo) + ", " + shortest(hi) + "]"};
}

CLI::Validator whole_check(int lo, int hi) {
  return {[lo, hi](std::string& text) {
            const std::string digits = !text.empty() && text[0] == '+' ? text.substr(1) : text;
            const bool whole =
                !digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos;
            const auto first = digits.find_first_not_of('0');
            const std::string significant = first == std::string::npos ? "0" : digits.substr(first);
            // More than 18 digits is beyond any bound here (and beyond long long).
            const long long v = !whole                    ? 0
                                : significant.size() > 18 ? std::numeric_limits<long long>::max()
                                                          : std::stoll(significant);
            if (!whole || v < lo || v > hi) {
              return "'" + text + "' is not a whole number in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]";
            }
            // CLI11 converts what the validator leaves, and reads a leading 0 as octal ("010"
            // was 8 steps) and 0x as hexadecimal: it gets the decimal digits alone.
            text = significant;
            return std::string();
          },
          "INTEGER in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]"};
}

SolveSpec::Treatment parse_treatment_flag(const std::string& s, Scheme scheme) {
  if (s != "mixed" && s != "multipliers") {
    throw CLI::ValidationError("--constraints",
                               "expected 'mixed' or 'multipliers' (got '" + s + "')");
  }
  if (!mixes(scheme)) {
    throw CLI::ValidationError("--constraints", treatment_refusal(scheme));
  }
  return s == "mixed" ? SolveSpec::Treatment::mixed : SolveSpec::Treatment::multipliers;
}

void add_step_option(CLI::App* cmd, std::optional<double>& step) {
  cmd->add_option("--step", step,
                  "fixed step of the Newmark family (newmark, hht, generalized_alpha) and of "
                  "rattle (overrides [solve] step)")
      ->check(decimal_range_check(1e-300, 1e300));
}

void check_settings(const std::string& scene, const SolveSpec& settings) {
  try {
    settings.validate();
  } catch (const std::invalid_argument& e) {
    throw SceneError(scene + ": " + e.what());
  }
}

Scheme parse_scheme_flag(const std::string& flag, const std::string& s) {
  if (const auto scheme = scheme_from_string(s)) return *scheme;
  throw CLI::ValidationError(flag, "unknown scheme '" + s + "' (expected " + scheme_names() + ")");
}

std::vector<Scheme> parse_scheme_list(const std::string& flag, const std::string& s) {
  std::vector<Scheme> out;
  for (const auto& name : split_list(flag, s)) {
    const Scheme scheme = parse_scheme_flag(flag, name);
    if (scheme == Scheme::automatic) throw CLI::ValidationError(flag, "name schemes, not 'auto'");
    out.push_back(scheme);
  }
  return out;
}

std::vector<std::string> split_list(const std::string& flag, const std::string& s) {
  std::vector<std::string> out;
  std::string item;
  for (char c : s + ",") {
    if (c == ',') {
      if (item.empty()) {
        throw CLI::ValidationError(flag, "an empty item in '" + s + "' (a stray comma?)");
      }
      if (std::find(out.begin(), out.end(), item) != out.end()) {
        throw CLI::ValidationError(flag, "'" + item + "' is listed twice in '" + s + "'");
      }
      out.push_back(item);
      item.clear();
    } else if (c != ' ') {
      item += c;
    }
  }
  return out;
}

}  // namespace condyn
