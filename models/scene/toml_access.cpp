#include "models/scene/toml_access.hpp"

#include <cctype>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "models/core/nearest_names.hpp"
#include "models/scene/scene_parser.hpp"

namespace condyn {

namespace {

// No scene key is more than a few tables deep (solve.baumgarte.alpha); 32 leaves room for anything.
constexpr int kMaxKeyDots = 32;

}  // namespace

/// toml++ 3.3 builds (and tears down) the tables of a dotted key or table header recursively, and
/// overflows the stack on keys of tens of thousands of components (`a.a.a. ... = 1`, a segfault).
/// Its own limit (TOML_MAX_NESTED_VALUES, 256) covers nested arrays and inline tables only. So,
/// before parsing: no run of dot-separated key parts outside strings and comments may have more
/// than kMaxKeyDots dots. A number has at most one dot, so values never trip this.
void check_key_depth(const std::string& text, const std::string& file) {
  const std::size_t n = text.size();
  int line = 1, dots = 0;
  std::size_t i = 0;
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      dots = 0;
      ++i;
    } else if (c == '#') {  // a comment runs to the end of the line
      while (i < n && text[i] != '\n') ++i;
    } else if (c == '"' || c == '\'') {  // a string: skipped; a quoted key part continues a run
      const std::string triple(3, c);
      const bool multi = text.compare(i, 3, triple) == 0;
      i += multi ? 3 : 1;
      while (i < n) {
        if (text[i] == '\n') {
          if (!multi) break;  // unterminated: the parser reports it
          ++line;
        }
        if (c == '"' && text[i] == '\\') {  // an escape: skip the escaped character
          if (i + 1 < n && text[i + 1] == '\n') ++line;
          i += 2;
          continue;
        }
        if (multi && text.compare(i, 3, triple) == 0) {
          i += 3;
          while (i < n && text[i] == c) ++i;  // up to two quotes may end the content
          break;
        }
        if (!multi && text[i] == c) {
          ++i;
          break;
        }
        ++i;
      }
    } else {
      const auto u = static_cast<unsigned char>(c);
      if (c == '.') {
        if (++dots > kMaxKeyDots) {
          throw SceneError(scene_message(file, SourcePoint{"", line},
                                         "a dotted key or table header nests more than " +
                                             std::to_string(kMaxKeyDots) + " tables deep"));
        }
      } else if (std::isalnum(u) == 0 && c != '_' && c != '-' && c != '+' && c != ' ' &&
                 c != '\t') {
        dots = 0;  // '=', brackets, braces, commas, ... end a key
      }
      ++i;
    }
  }
}

namespace {

/// The number token that starts at (line, column) of `text` (both 1-based; toml++ counts columns
/// in code points, so a name with é earlier on the line moves the byte offset), or "".
std::string number_token(const std::vector<std::size_t>& line_starts, const std::string& text,
                         const toml::source_position& at) {
  if (at.line < 1 || at.line > line_starts.size() || at.column < 1) return {};
  std::size_t i = line_starts[at.line - 1];
  for (std::size_t c = 1; c < at.column && i < text.size() && text[i] != '\n'; ++c) {
    ++i;  // past the code point's lead byte and its continuation bytes
    while (i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0U) == 0x80U) ++i;
  }
  std::size_t end = i;
  while (end < text.size() &&
         (std::isalnum(static_cast<unsigned char>(text[end])) != 0 || text[end] == '.' ||
          text[end] == '+' || text[end] == '-' || text[end] == '_')) {
    ++end;
  }
  return i < end ? text.substr(i, end - i) : std::string();
}

/// Whether a float literal's mantissa (before its exponent) has a nonzero digit.
bool nonzero_mantissa(const std::string& token) {
  for (const char c : token) {
    if (c == 'e' || c == 'E') return false;
    if (c >= '1' && c <= '9') return true;
  }
  return false;
}

void check_underflow(const TomlAccess& access, const toml::node& node, const std::string& path,
                     const std::vector<std::size_t>& line_starts, const std::string& text) {
  if (const auto* t = node.as_table()) {
    for (const auto& [key, value] : *t) {
      check_underflow(access, value, TomlAccess::join(path, std::string(key.str())), line_starts,
                      text);
    }
  } else if (const auto* a = node.as_array()) {
    for (std::size_t i = 0; i < a->size(); ++i) {
      check_underflow(access, *a->get(i), TomlAccess::index(path, i), line_starts, text);
    }
  } else if (const auto* f = node.as_floating_point(); f != nullptr && f->get() == 0.0) {
    const std::string token = number_token(line_starts, text, node.source().begin);
    if (nonzero_mantissa(token)) {
      access.fail(node, path,
                  token +
                      " is nonzero but below the smallest double (4.9e-324) in magnitude, and "
                      "would be read as 0 (write 0 if 0 is meant)");
    }
  }
}

}  // namespace

void check_number_range(const toml::table& root, const std::string& text, const std::string& file) {
  std::vector<std::size_t> line_starts{0};
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n') line_starts.push_back(i + 1);
  }
  check_underflow(TomlAccess(file), root, "", line_starts, text);
}

SourcePoint TomlAccess::at(const toml::node& node, const std::string& path) const {
  return SourcePoint{path, static_cast<int>(node.source().begin.line)};
}

void TomlAccess::fail(const toml::node& node, const std::string& path,
                      const std::string& problem) const {
  throw SceneError(scene_message(file_, at(node, path), problem));
}

void TomlAccess::check_keys(const toml::table& table, const std::string& path,
                            std::initializer_list<std::string_view> allowed) const {
  for (const auto& [key, node] : table) {
    bool known = false;
    for (auto a : allowed) known = known || key.str() == a;
    if (!known) {
      const std::vector<std::string> keys(allowed.begin(), allowed.end());
      const std::vector<std::string> near = nearest_names(std::string(key.str()), keys, 1);
      fail(node, join(path, std::string(key.str())),
           "unknown key (" + (near.empty() ? std::string() : "did you mean " + near[0] + "? ") +
               "expected one of: " + joined_names(keys) + ")");
    }
  }
}

std::string TomlAccess::join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string TomlAccess::index(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i + 1) + "]";
}

const toml::table& TomlAccess::table(const toml::node& node, const std::string& path) const {
  if (const auto* t = node.as_table()) return *t;
  fail(node, path, "expected a table");
}

const toml::array& TomlAccess::array(const toml::node& node, const std::string& path) const {
  if (const auto* a = node.as_array()) return *a;
  fail(node, path, "expected an array");
}

double TomlAccess::number(const toml::node& node, const std::string& path) const {
  double v = 0.0;
  if (const auto* f = node.as_floating_point()) {
    v = f->get();
  } else if (const auto* i = node.as_integer()) {
    v = static_cast<double>(i->get());
  } else {
    fail(node, path, "expected a number");
  }
  if (!std::isfinite(v)) fail(node, path, "must be finite");
  return v;
}

double TomlAccess::positive(const toml::node& node, const std::string& path) const {
  const double v = number(node, path);
  if (v <= 0.0) fail(node, path, "must be > 0 (got " + fmt(v) + ")");
  return v;
}

std::string TomlAccess::string(const toml::node& node, const std::string& path) const {
  if (const auto* s = node.as_string()) return s->get();
  fail(node, path, "expected a string");
}

long TomlAccess::integer(const toml::node& node, const std::string& path) const {
  if (const auto* i = node.as_integer()) return static_cast<long>(i->get());
  fail(node, path, "expected an integer");
}

const toml::node& TomlAccess::required(const toml::table& t, const std::string& path,
                                       std::string_view key) const {
  if (const auto* n = t.get(key)) return *n;
  fail(t, join(path, std::string(key)), "missing required key");
}

std::vector<double> TomlAccess::numbers(const toml::node& node, const std::string& path) const {
  std::vector<double> out;
  const auto& arr = array(node, path);
  for (std::size_t i = 0; i < arr.size(); ++i) out.push_back(number(*arr.get(i), index(path, i)));
  return out;
}

std::vector<std::vector<double>> TomlAccess::dense_matrix(const toml::node& node,
                                                          const std::string& path) const {
  std::vector<std::vector<double>> rows;
  const auto& arr = array(node, path);
  for (std::size_t i = 0; i < arr.size(); ++i) rows.push_back(numbers(*arr.get(i), index(path, i)));
  return rows;
}

std::vector<std::pair<std::string, double>> TomlAccess::dof_values(const toml::node& node,
                                                                   const std::string& path,
                                                                   std::vector<int>* lines) const {
  std::vector<std::pair<std::string, double>> out;
  const auto& t = table(node, path);
  for (const auto& [key, value] : t) {
    out.emplace_back(std::string(key.str()), number(value, join(path, std::string(key.str()))));
    if (lines != nullptr) lines->push_back(static_cast<int>(value.source().begin.line));
  }
  return out;
}

std::string TomlAccess::fmt(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

}  // namespace condyn
