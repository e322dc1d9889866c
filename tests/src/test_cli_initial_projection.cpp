// [initial] project = true from the command line: `run` and `info` say, per DOF, what the
// projection moved, and nothing about the values the scene gave.
#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "tests/cli_sandbox.hpp"

namespace test_cli_initial_projection {

namespace {

std::string four_bar_text() {
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/four_bar.toml");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("run and info print, per DOF, what the projection moved") {
  condyn::test::Sandbox box;
  box.write("four_bar.toml", four_bar_text());
  for (const std::string command : {"info four_bar.toml", "run four_bar.toml --out f.csv"}) {
    CAPTURE(command);
    const auto r = box.run(command);
    REQUIRE(r.code == 0);
    CHECK(r.out.find("keeping the 1 value given in [initial]") != std::string::npos);
    CHECK(r.out.find("  ux3: velocity 0 -> ") != std::string::npos);
    CHECK(r.out.find("ux2: velocity") == std::string::npos);  // given, kept
    CHECK(r.out.find("ux1:") == std::string::npos);           // support, did not move
  }
}

}  // namespace test_cli_initial_projection
