// Issue 43, item 4: the line reader shared by the Matrix Market and time-table readers
// (models/core/line_reader.hpp): line endings LF, CRLF and lone CR, mixed in one text; a byte
// order mark dropped from the first line only; line numbers counted as the messages name them;
// and both readers naming the same line of the same text.
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/line_reader.hpp"
#include "models/core/time_table.hpp"
#include "models/scene/matrix_market.hpp"

using namespace condyn;

namespace test_line_reader {

namespace {

/// Every line the reader serves, and the number it gives each.
std::vector<std::pair<std::string, int>> lines_of(const std::string& text) {
  std::istringstream in(text);
  LineReader reader(in);
  std::vector<std::pair<std::string, int>> out;
  std::string_view line;
  while (reader.next(line)) out.emplace_back(std::string(line), reader.line_number());
  CHECK_FALSE(reader.failed());
  return out;
}

using Lines = std::vector<std::pair<std::string, int>>;

}  // namespace

TEST_CASE("line reader: LF, CRLF and lone CR endings, mixed, each line numbered") {
  CHECK(lines_of("") == Lines{});
  CHECK(lines_of("a") == Lines{{"a", 1}});
  CHECK(lines_of("a\nb\n") == Lines{{"a", 1}, {"b", 2}});
  CHECK(lines_of("a\r\nb\r\n") == Lines{{"a", 1}, {"b", 2}});
  CHECK(lines_of("a\rb\r") == Lines{{"a", 1}, {"b", 2}});
  // Mixed endings; blank lines are lines (counted), a CR before CRLF is an empty line of its own.
  CHECK(lines_of("a\r\n\nb\rc\r\r\nd") ==
        Lines{{"a", 1}, {"", 2}, {"b", 3}, {"c", 4}, {"", 5}, {"d", 6}});
  // The last line needs no ending; a final ending adds no empty line.
  CHECK(lines_of("a\nb") == Lines{{"a", 1}, {"b", 2}});
  CHECK(lines_of("a\n\n") == Lines{{"a", 1}, {"", 2}});
}

TEST_CASE("line reader: a byte order mark is dropped from the first line only") {
  const std::string bom = "\xEF\xBB\xBF";
  CHECK(lines_of(bom + "a\r\nb") == Lines{{"a", 1}, {"b", 2}});
  CHECK(lines_of(bom) == Lines{{"", 1}});
  // One on a later line is text (neither format writes it there): kept, to be refused by the
  // reader of that line.
  CHECK(lines_of("a\n" + bom + "b") == Lines{{"a", 1}, {bom + "b", 2}});
}

TEST_CASE("line reader: Matrix Market and tables name the same line of the same endings") {
  // The bad value sits on line 5 of each text however its lines end: both readers count the
  // lines the shared reader serves.
  for (const std::string eol : {"\n", "\r\n", "\r"}) {
    CAPTURE(eol.size());
    const std::string market = "%%MatrixMarket matrix coordinate real general" + eol + "%" + eol +
                               "2 2 2" + eol + "1 1 1.0" + eol + "2 2 x" + eol;
    try {
      (void)parse_matrix_market(market);
      FAIL("the bad value was accepted");
    } catch (const MatrixMarketError& e) {
      CHECK(e.line() == 5);
    }
    const std::string table = "# t, v" + eol + "t,v" + eol + eol + "0,1" + eol + "1,x" + eol;
    try {
      (void)parse_time_table(table, "v");
      FAIL("the bad value was accepted");
    } catch (const TimeTableError& e) {
      CHECK(e.line() == 5);
    }
  }
}

}  // namespace test_line_reader
