// What reaches the terminal holds no control sequence from the input: control characters are
// shown as \xNN, everything else (line feeds, tabs, UTF-8 text) passes byte for byte.
#include <doctest/doctest.h>

#include <ostream>
#include <sstream>
#include <string>

#include "src/output/escaped_streams.hpp"

namespace test_escaped_streams {

using condyn::EscapingStreambuf;

namespace {

/// What `pieces`, written one after another (each its own <<, flushed between), come out as.
std::string shown(std::initializer_list<std::string> pieces) {
  std::stringbuf sink;
  EscapingStreambuf escaping(&sink);
  std::ostream out(&escaping);
  for (const auto& piece : pieces) out << piece << std::flush;
  CHECK(out.good());
  return sink.str();
}

}  // namespace

TEST_CASE("control characters are shown escaped, text passes unchanged") {
  CHECK(shown({"error: plain.toml:3: key\n\tnext line\n"}) ==
        "error: plain.toml:3: key\n\tnext line\n");
  CHECK(shown({"a\x1b[2Jb.toml"}) == "a\\x1b[2Jb.toml");
  CHECK(shown({"x\ry"}) == "x\\x0dy");
  CHECK(shown({"bell\x07 and del\x7f"}) == "bell\\x07 and del\\x7f");
  CHECK(shown({std::string("nul\0here", 8)}) == "nul\\x00here");
  // UTF-8 text, including U+00A0..U+00FF (lead byte 0xC2/0xC3) and 4-byte sequences.
  const std::string utf8 = "m\xc2\xb2 \xc3\xa9t\xc3\xa9 \xe2\x80\x94 \xf0\x9f\x94\xa9 \xc2\xa0";
  CHECK(shown({utf8}) == utf8);
}

TEST_CASE("C1 controls are escaped whether UTF-8 encoded or stray bytes") {
  // (Each escape is followed by a letter that is no hex digit: "\x9bm" is two characters.)
  CHECK(shown({"csi\xc2\x9bm"}) == "csi\\xc2\\x9bm");
  CHECK(shown({"nel\xc2\x85."}) == "nel\\xc2\\x85.");
  CHECK(shown({"stray\x9bJ"}) == "stray\\x9bJ");
  // A continuation byte 0x80..0x9F inside a longer sequence is text (U+2014 is E2 80 94).
  CHECK(shown({"\xe2\x80\x94"}) == "\xe2\x80\x94");
  // A 0xC2 split from its next byte by a flush is still decided by that byte.
  CHECK(shown({"a\xc2", "\x9bz"}) == "a\\xc2\\x9bz");
  CHECK(shown({"a\xc2", "\xb0z"}) == "a\xc2\xb0z");
  CHECK(shown({"a\xc2", "\n"}) == "a\xc2\n");
  // Character by character, as operator<<(char) writes.
  std::stringbuf sink;
  EscapingStreambuf escaping(&sink);
  std::ostream out(&escaping);
  for (const char c : std::string("p\x1bq\xc2\x9br\xc3\xa9")) out << c;
  CHECK(sink.str() == "p\\x1bq\\xc2\\x9br\xc3\xa9");
}

TEST_CASE("a sink that fails fails the stream") {
  // A stringbuf opened for reading only takes no output.
  std::stringbuf sink(std::ios::in);
  EscapingStreambuf escaping(&sink);
  std::ostream out(&escaping);
  out << "text" << std::flush;
  CHECK_FALSE(out.good());
  std::ostream escaped_only(&escaping);
  escaped_only << "\x1b" << std::flush;
  CHECK_FALSE(escaped_only.good());
}

}  // namespace test_escaped_streams
