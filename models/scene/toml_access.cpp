#include "models/scene/toml_access.hpp"

#include <algorithm>
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

/// The scene's text by toml++'s source positions (1-based lines and columns; columns count code
/// points, so a name with é earlier on the line moves the byte offset). A column is found in O(1)
/// on a line of ASCII and, on other lines, by walking on from the last column asked for there:
/// a matrix written on one line (a 400 x 400 stiffness, 160,000 numbers) is read in one pass where
/// walking from the line's start for each number took minutes.
class SourceColumns {
 public:
  explicit SourceColumns(const std::string& text) : text_(text) {
    line_starts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') line_starts_.push_back(i + 1);
      if ((static_cast<unsigned char>(text[i]) & 0x80U) != 0U) {
        if (wide_lines_.empty() || wide_lines_.back() != line_starts_.size() - 1)
          wide_lines_.push_back(line_starts_.size() - 1);
      }
    }
  }

  /// The number token that starts at `at`, or "".
  [[nodiscard]] std::string number_token(const toml::source_position& at) {
    if (at.line < 1 || at.line > line_starts_.size() || at.column < 1) return {};
    const std::size_t line = at.line - 1;
    std::size_t i = line_starts_[line] + (at.column - 1);
    if (std::binary_search(wide_lines_.begin(), wide_lines_.end(), line))
      i = wide_offset(line, at.column);
    std::size_t end = i;
    while (end < text_.size() &&
           (std::isalnum(static_cast<unsigned char>(text_[end])) != 0 || text_[end] == '.' ||
            text_[end] == '+' || text_[end] == '-' || text_[end] == '_')) {
      ++end;
    }
    return i < end ? text_.substr(i, end - i) : std::string();
  }

 private:
  /// The byte offset of `column` on a line holding multi-byte code points: on from the last
  /// column found on that line when it lies before, else from the line's start.
  std::size_t wide_offset(std::size_t line, std::size_t column) {
    if (cursor_line_ != line || cursor_column_ > column) {
      cursor_line_ = line;
      cursor_column_ = 1;
      cursor_ = line_starts_[line];
    }
    while (cursor_column_ < column && cursor_ < text_.size() && text_[cursor_] != '\n') {
      ++cursor_;  // past the code point's lead byte and its continuation bytes
      while (cursor_ < text_.size() &&
             (static_cast<unsigned char>(text_[cursor_]) & 0xC0U) == 0x80U)
        ++cursor_;
      ++cursor_column_;
    }
    return cursor_;
  }

  const std::string& text_;
  std::vector<std::size_t> line_starts_;
  std::vector<std::size_t> wide_lines_;  ///< ascending: the lines with a byte of 0x80 or more
  std::size_t cursor_line_ = 0, cursor_column_ = 1, cursor_ = 0;
};

/// Whether a float literal's mantissa (before its exponent) has a nonzero digit.
bool nonzero_mantissa(const std::string& token) {
  for (const char c : token) {
    if (c == 'e' || c == 'E') return false;
    if (c >= '1' && c <= '9') return true;
  }
  return false;
}

void check_underflow(const TomlAccess& access, const toml::node& node, const std::string& path,
                     SourceColumns& columns) {
  if (const auto* t = node.as_table()) {
    for (const auto& [key, value] : *t) {
      check_underflow(access, value, TomlAccess::join(path, std::string(key.str())), columns);
    }
  } else if (const auto* a = node.as_array()) {
    for (std::size_t i = 0; i < a->size(); ++i) {
      check_underflow(access, *a->get(i), TomlAccess::index(path, i), columns);
    }
  } else if (const auto* f = node.as_floating_point(); f != nullptr && f->get() == 0.0) {
    const std::string token = columns.number_token(node.source().begin);
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
  SourceColumns columns(text);
  check_underflow(TomlAccess(file), root, "", columns);
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
