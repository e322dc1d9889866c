// The strict Matrix Market reader (why not Eigen's loadMarket: models/scene/matrix_market.hpp).

#include "models/scene/matrix_market.hpp"

#include "models/core/line_reader.hpp"
#include "models/core/memory_estimate.hpp"
#include "models/core/number_cell.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

namespace condyn {

namespace {

// A lying size line must not make the reader reserve gigabytes before the first entry is read.
constexpr long long kMaxReserve = 10'000'000;

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

/// The whitespace-separated tokens of a line (views into it): the first kMaxTokens, and how many
/// there are in all. No allocation: an entry line is read millions of times.
struct Tokens {
  static constexpr std::size_t kMaxTokens = 6;
  std::array<std::string_view, kMaxTokens> views;
  std::size_t count = 0;
  [[nodiscard]] bool empty() const { return count == 0; }
  [[nodiscard]] std::size_t size() const { return count; }
  [[nodiscard]] std::string_view operator[](std::size_t k) const { return views.at(k); }
};

Tokens tokens(std::string_view line) {
  Tokens out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) {
      if (out.count < Tokens::kMaxTokens) out.views.at(out.count) = line.substr(start, i - start);
      ++out.count;
    }
  }
  return out;
}

long long to_integer(std::string_view s, int line, const char* what) {
  long long v = 0;
  // A leading '+' is a sign, as C's strtoll takes it (from_chars does not).
  const bool plus = !s.empty() && s.front() == '+';
  const std::string_view digits = plus ? s.substr(1) : s;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  const bool whole = !digits.empty() && !(plus && (digits.front() == '+' || digits.front() == '-'));
  if (whole && ec == std::errc::result_out_of_range) {
    throw MatrixMarketError(
        line, std::string(what) + " '" + shown_cell(s) + "' is out of range (beyond 2^63 - 1)");
  }
  if (!whole || ec != std::errc() || end != digits.data() + digits.size()) {
    throw MatrixMarketError(line, std::string(what) + " '" + shown_cell(s) + "' is not an integer");
  }
  return v;
}

/// Whether s is an optional sign and decimal digits only (no point, no exponent).
bool whole_number_text(std::string_view s) {
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) s.remove_prefix(1);
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// 2^53: every integer up to it is a double; above, only some are.
constexpr double kMaxExactInteger = 9007199254740992.0;

/// An integer written in digits that the double v, read from it, does not hold exactly: refused,
/// since the 'integer' field promises exact values (9007199254740993 became ...992 silently).
void inexact_integer(std::string_view text, double v, int line) {
  if (!whole_number_text(text)) return;  // an exponent form ('1e20') says which double it means
  std::string_view digits = text;
  if (digits.front() == '+' || digits.front() == '-') digits.remove_prefix(1);
  while (digits.size() > 1 && digits.front() == '0') digits.remove_prefix(1);
  std::array<char, 400> held{};
  const auto [end, ec] = std::to_chars(held.data(), held.data() + held.size(), std::abs(v),
                                       std::chars_format::fixed, 0);
  if (ec == std::errc() && std::string_view(held.data(), end - held.data()) == digits) return;
  throw MatrixMarketError(line, "the integer '" + shown_cell(text) +
                                    "' is beyond 2^53 and not held exactly by a double (it would "
                                    "be " +
                                    std::string(held.data(), end) +
                                    "); write the value meant, or the field 'real'");
}

double to_double(std::string_view s, int line) {
  double v = 0.0;
  if (const NumberCell kind = parse_number_cell(s, v); kind != NumberCell::ok) {
    throw MatrixMarketError(line, "the value '" + shown_cell(s) + "' " + number_cell_problem(kind));
  }
  if (!std::isfinite(v)) {
    throw MatrixMarketError(line, "the value '" + shown_cell(s) + "' is not finite");
  }
  return v;
}

}  // namespace

std::optional<std::string> size_range_refusal(long long rows, long long cols) {
  constexpr long long kMaxIndex = std::numeric_limits<int>::max();
  if (rows >= 1 && cols >= 1 && rows <= kMaxIndex && cols <= kMaxIndex) return std::nullopt;
  return "the size " + std::to_string(rows) + " x " + std::to_string(cols) +
         " is not between 1 and 2^31 - 1";
}

std::optional<std::string> holding_refusal(long long rows, long long cols, double entries,
                                           bool rows_are_dofs) {
  // setFromTriplets holds a row-major copy beside the column-major result: 4 + 4 bytes per row
  // and per column, and per entry the triplet (16) and two copies of index and value (24).
  const double stored =
      8.0 * (static_cast<double>(rows) + static_cast<double>(cols)) + 40.0 * entries;
  double integrating = 0.0;  // a model matrix: what a run of that many DOFs holds at least
  if (rows_are_dofs) {
    ModelSizes sizes;
    sizes.dofs = static_cast<double>(rows);
    sizes.nnz_stiffness = entries;
    integrating = least_memory_estimate(sizes).lower_bound;
  }
  const double needed = stored + integrating;
  const auto available = available_memory_bytes();
  if (!available || needed <= *available) return std::nullopt;
  return (rows_are_dofs ? "holding it and integrating a model of " + std::to_string(rows) +
                              " DOFs needs at least "
                        : std::string("holding it needs ")) +
         format_bytes(needed) + ", more than the " + format_bytes(*available) +
         " this machine has available (MemAvailable in /proc/meminfo)";
}

namespace {

/// What the header line says of the values.
struct MarketHeader {
  bool dense = false;      ///< format 'array': every value, column by column
  bool integer = false;    ///< field 'integer'
  bool symmetric = false;  ///< the lower triangle only
};

/// The first line: '%%MatrixMarket matrix FORMAT FIELD SYMMETRY', of the formats, fields and
/// symmetries read here.
MarketHeader read_header(LineReader& lines) {
  std::string_view line;
  if (!lines.next(line)) throw MatrixMarketError(0, "the file is empty");
  const auto head = tokens(line);
  if (head.empty() || lower(head[0]) != "%%matrixmarket") {
    throw MatrixMarketError(1, "the first line is not a Matrix Market header (%%MatrixMarket ...)");
  }
  if (head.size() != 5 || lower(head[1]) != "matrix") {
    throw MatrixMarketError(
        1, "the header must read '%%MatrixMarket matrix coordinate real general' (or symmetric)");
  }
  const std::string format = lower(head[2]), field = lower(head[3]), symmetry = lower(head[4]);
  // 'array' is what scipy.io.mmwrite writes for a numpy array (a load pattern or a right-hand
  // side as a column, or a small dense matrix): its values column by column, one per line, the
  // lower triangle only when symmetric. Its zeros are not stored.
  if (format != "coordinate" && format != "array") {
    throw MatrixMarketError(1, "format '" + format +
                                   "' is not supported: only 'coordinate' (sparse) or 'array' "
                                   "(dense, column by column)");
  }
  if (field != "real" && field != "integer") {
    throw MatrixMarketError(1,
                            "field '" + field + "' is not supported: only 'real' (or 'integer')");
  }
  if (symmetry != "general" && symmetry != "symmetric") {
    throw MatrixMarketError(
        1, "symmetry '" + symmetry + "' is not supported: only 'general' or 'symmetric'");
  }
  return {format == "array", field == "integer", symmetry == "symmetric"};
}

/// What the size line declares, and its line.
struct MarketSize {
  long long rows = 0, cols = 0, entries = 0;
  int line = 0;
};

/// The size line: the first line after the header that is neither a comment nor blank; rows and
/// columns in range, and a symmetric matrix square. The entry count is checked by check_size.
MarketSize read_size_line(LineReader& lines, const MarketHeader& header) {
  std::string_view line;
  Tokens size;
  while (lines.next(line)) {
    if (!line.empty() && line.front() == '%') continue;
    size = tokens(line);
    if (!size.empty()) break;
  }
  const int line_no = lines.line_number();
  const bool dense = header.dense;
  if (size.empty())
    throw MatrixMarketError(line_no, "the size line (rows cols entries) is missing");
  if (size.size() != (dense ? 2U : 3U)) {
    throw MatrixMarketError(line_no, dense ? "the size line of an array must hold two integers: "
                                             "rows cols"
                                           : "the size line must hold three integers: rows cols "
                                             "entries");
  }
  // A size line of the right length but not of integers is most often an entry where the size
  // line was left out: say so (the entry count '1.0' alone sent users to the wrong line).
  for (std::size_t k = 0; k < size.size(); ++k) {
    const std::string_view token = size[k];
    if (!whole_number_text(token)) {
      throw MatrixMarketError(
          line_no, "the size line (" + std::string(dense ? "rows cols" : "rows cols entries") +
                       ", the first line after the header and comments) holds '" +
                       shown_cell(token) +
                       "', not a whole number: is the size line missing, with an entry in its "
                       "place?");
    }
  }
  MarketSize out;
  out.line = line_no;
  out.rows = to_integer(size[0], line_no, "the row count");
  out.cols = to_integer(size[1], line_no, "the column count");
  const long long rows = out.rows, cols = out.cols;
  if (const auto refusal = size_range_refusal(rows, cols)) {
    throw MatrixMarketError(line_no, *refusal);
  }
  if (header.symmetric && rows != cols) {
    throw MatrixMarketError(line_no, "a symmetric matrix must be square (the file says " +
                                         std::to_string(rows) + " x " + std::to_string(cols) + ")");
  }
  // An array holds every value (the lower triangle when symmetric): rows, cols < 2^31, so the
  // product fits in 63 bits.
  out.entries = !dense             ? to_integer(size[2], line_no, "the entry count")
                : header.symmetric ? rows * (rows + 1) / 2
                                   : rows * cols;
  return out;
}

/// The declared size against what the caller expects and what this machine can hold, before
/// anything is allocated.
void check_size(const MarketSize& size, const MarketHeader& header,
                const MarketExpectation& expect) {
  const long long rows = size.rows, cols = size.cols, entries = size.entries;
  const int line_no = size.line;
  if ((expect.rows > 0 && rows != expect.rows) || (expect.cols > 0 && cols != expect.cols)) {
    throw MatrixMarketError(line_no, "the size line declares " + std::to_string(rows) + " x " +
                                         std::to_string(cols) + " but " + expect.because + ": " +
                                         expect.advice);
  }
  // What holding it takes, before anything is allocated: a size line of 2·10⁹ (a typo, or
  // another file's) had the kernel kill the process while the index arrays were filled.
  const double stored_entries = static_cast<double>(entries) * (header.symmetric ? 2.0 : 1.0);
  if (const auto refusal = holding_refusal(rows, cols, stored_entries, expect.rows_are_dofs)) {
    throw MatrixMarketError(line_no, "the size line declares " + std::to_string(rows) + " x " +
                                         std::to_string(cols) + " with " + std::to_string(entries) +
                                         " entries: " + *refusal + "; is the size line right?");
  }
  // No upper bound from rows x cols: duplicate entries are allowed (and summed).
  if (entries < 0) {
    throw MatrixMarketError(line_no, "the entry count " + std::to_string(entries) + " is negative");
  }
  // Fewer entries than rows leaves a row empty: refused here, before rows of index arrays are
  // filled (2·10⁹ rows with 2 entries would fill gigabytes before "row 3 has no entry").
  if (!header.dense && expect.rows_need_entries && entries < rows) {
    throw MatrixMarketError(line_no, "the size line declares " + std::to_string(rows) +
                                         " rows but " + std::to_string(entries) +
                                         " entries, so some row has none: every constraint row "
                                         "needs a coefficient; is the size line right?");
  }
}

/// The value of an entry: finite, and a whole number held exactly when the field is 'integer'.
double entry_value(std::string_view text, const MarketHeader& header, int line_no) {
  const double v = to_double(text, line_no);
  if (header.integer && v != std::trunc(v)) {
    throw MatrixMarketError(line_no, "the value '" + std::string(text) +
                                         "' is not an integer, as the header's field "
                                         "'integer' says every value is");
  }
  if (header.integer && std::abs(v) >= kMaxExactInteger) inexact_integer(text, v, line_no);
  return v;
}

/// The entries after the size line, as triplets (both triangles of a symmetric matrix; an
/// array's zeros left out): exactly as many as the size line declares, each inside the matrix.
std::vector<Eigen::Triplet<double>> read_entries(LineReader& lines, const MarketHeader& header,
                                                 const MarketSize& size) {
  const bool dense = header.dense, symmetric = header.symmetric;
  const long long rows = size.rows, cols = size.cols, entries = size.entries;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(std::min(entries * (symmetric ? 2 : 1), kMaxReserve)));
  long long read = 0;
  long long next_row = 1, next_col = 1;  // an array's next position, column by column
  std::string_view line;
  while (lines.next(line)) {
    const int line_no = lines.line_number();
    if (!line.empty() && line.front() == '%') continue;
    const auto tok = tokens(line);
    if (tok.empty()) continue;
    if (read == entries) {
      throw MatrixMarketError(line_no, "more entries than the " + std::to_string(entries) +
                                           " the size line (line " + std::to_string(size.line) +
                                           ") declares");
    }
    if (tok.size() != (dense ? 1U : 3U)) {
      throw MatrixMarketError(line_no, std::string(dense ? "an array's line holds one value"
                                                         : "an entry is 'row column value'") +
                                           " (found " + std::to_string(tok.size()) + " fields)");
    }
    const long long i = dense ? next_row : to_integer(tok[0], line_no, "the row index");
    const long long j = dense ? next_col : to_integer(tok[1], line_no, "the column index");
    if (dense && ++next_row > rows) {
      ++next_col;
      next_row = symmetric ? next_col : 1;
    }
    if (i < 1 || i > rows || j < 1 || j > cols) {
      throw MatrixMarketError(line_no, "the index (" + std::to_string(i) + ", " +
                                           std::to_string(j) + ") lies outside the " +
                                           std::to_string(rows) + " x " + std::to_string(cols) +
                                           " matrix of the size line, line " +
                                           std::to_string(size.line) + " (indices are 1-based)");
    }
    if (symmetric && j > i) {
      throw MatrixMarketError(line_no, "the entry (" + std::to_string(i) + ", " +
                                           std::to_string(j) +
                                           ") lies above the diagonal: a symmetric file holds the "
                                           "lower triangle only");
    }
    const double v = entry_value(tok[dense ? 0 : 2], header, line_no);
    const auto r = static_cast<int>(i - 1), c = static_cast<int>(j - 1);
    ++read;
    if (dense && v == 0.0) continue;
    trip.emplace_back(r, c, v);
    if (symmetric && r != c) trip.emplace_back(c, r, v);
  }
  if (read != entries) {
    throw MatrixMarketError(lines.line_number(), "the file ends after " + std::to_string(read) +
                                                     " of the " + std::to_string(entries) +
                                                     " entries the size line (line " +
                                                     std::to_string(size.line) + ") declares");
  }
  return trip;
}

/// Reads the file line by line from `in`: never more than one line of it in memory (a stiffness
/// file of a million DOFs is 300 MB of text).
MarketMatrix parse_market_stream(std::istream& in, const MarketExpectation& expect) {
  LineReader lines(in);
  const MarketHeader header = read_header(lines);
  const MarketSize size = read_size_line(lines, header);
  check_size(size, header, expect);
  const auto trip = read_entries(lines, header, size);
  MarketMatrix out;
  out.symmetric = header.symmetric;
  out.matrix.resize(static_cast<Eigen::Index>(size.rows), static_cast<Eigen::Index>(size.cols));
  out.matrix.setFromTriplets(trip.begin(), trip.end());  // duplicates are summed
  out.matrix.makeCompressed();
  for (Eigen::Index k = 0; k < out.matrix.nonZeros(); ++k) {
    if (!std::isfinite(out.matrix.valuePtr()[k])) {
      throw MatrixMarketError(0, "duplicate entries add up beyond the double range");
    }
  }
  if (lines.failed()) throw MatrixMarketError(lines.line_number(), "cannot read the file");
  return out;
}

}  // namespace

MarketMatrix parse_matrix_market(const std::string& text, const MarketExpectation& expect) {
  std::istringstream in(text);
  return parse_market_stream(in, expect);
}

MarketMatrix read_matrix_market(const std::string& path, const MarketExpectation& expect) {
  // A device or a pipe (/dev/zero, a FIFO) would be read forever or block: regular files only.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw MatrixMarketError(0, "is not a regular file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MatrixMarketError(0, "cannot open the file");
  return parse_market_stream(in, expect);
}

}  // namespace condyn
