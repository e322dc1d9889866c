// info's wrapped report lines (src/reports/wrapped_lines.hpp): within kReportWidth columns,
// continuation lines under the text, long lists counted after kMaxListLines lines.
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "src/reports/wrapped_lines.hpp"

using namespace condyn;

namespace test_wrapped_lines {

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

TEST_CASE("wrapped_text keeps every line within the width, the words and their order") {
  std::string text;
  for (int k = 0; k < 60; ++k) text += (k ? " " : "") + std::string("word") + std::to_string(k);
  const std::string out = wrapped_text("memory: ", text);
  REQUIRE(out.back() == '\n');
  const auto lines = lines_of(out);
  REQUIRE(lines.size() > 1);
  CHECK(lines.front().rfind("memory: word0 word1", 0) == 0);
  std::string words;
  for (const auto& line : lines) {
    CHECK(line.size() <= kReportWidth);
    if (&line != &lines.front()) CHECK(line.rfind("        word", 0) == 0);  // under the text
    words += (words.empty() ? "" : " ") + line.substr(8);
  }
  CHECK(words == text);
  // Text of several lines is the caller's layout: printed as it is.
  CHECK(wrapped_text("a: ", "one\ntwo") == "a: one\ntwo\n");
  // A word longer than the width stays whole on its line.
  const std::string long_word(150, 'x');
  CHECK(wrapped_text("a: ", "b " + long_word) == "a: b\n   " + long_word + "\n");
}

TEST_CASE("wrapped_list counts what it does not show after kMaxListLines lines") {
  CHECK(wrapped_list("masters: ", {}) == "masters: none\n");
  CHECK(wrapped_list("masters: ", {"u1", "u2"}) == "masters: u1, u2\n");
  std::vector<std::string> names;
  for (int k = 0; k < 598; ++k) names.push_back("ux" + std::to_string(k));
  const auto lines = lines_of(wrapped_list("masters: ", names));
  REQUIRE(lines.size() == kMaxListLines);
  std::size_t shown = 0;
  for (const auto& line : lines) {
    CHECK(line.size() <= kReportWidth);
    for (char c : line) shown += c == ',' ? 1 : 0;
  }
  // Every name shown ends in a comma (more follow): the count names the rest and the whole.
  const std::string suffix =
      "... and " + std::to_string(names.size() - shown) + " more (598 in all)";
  CHECK(lines.back().size() >= suffix.size());
  CHECK(lines.back().substr(lines.back().size() - suffix.size()) == suffix);
}

}  // namespace test_wrapped_lines
