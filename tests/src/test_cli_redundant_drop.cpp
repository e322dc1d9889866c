// [solve] redundant = "drop" on a mechanism's rows on the command line: `run` and `info` name the
// dropped rigid member and say that the reactions of the set are not unique; without drop the
// scene is refused (exit 2), the dependent rows named.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/cli_sandbox.hpp"

namespace test_cli_redundant_drop {

namespace {

std::string scene_text() {
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) +
                   "/models/scenes/parallelogram_redundant_bar.toml");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("run and info name the redundant bar they drop and say its reactions are not unique") {
  condyn::test::Sandbox box;
  box.write("r.toml", scene_text());
  const auto run = box.run("run r.toml --out r.csv");
  CAPTURE(run.out);
  CAPTURE(run.err);
  REQUIRE(run.code == 0);
  CHECK(has(run.out, "dropped redundant constraint 'rigid_"));
  CHECK(has(run.out, "; their reactions carry its force too: not unique)"));
  const auto info = box.run("info r.toml");
  CAPTURE(info.out);
  REQUIRE(info.code == 0);
  CHECK(has(info.out, "dropped redundant constraint 'rigid_"));
  CHECK(has(info.out, "not unique"));
}

TEST_CASE("without drop the redundant bar is refused with exit 2, the dependent rows named") {
  condyn::test::Sandbox box;
  std::string text = scene_text();
  const std::string drop = "redundant = \"drop\"\n";
  text.erase(text.find(drop), drop.size());
  box.write("r.toml", text);
  const auto run = box.run("run r.toml --out r.csv");
  CAPTURE(run.err);
  CHECK(run.code == 2);
  CHECK(has(run.err, "are linearly dependent at the initial configuration"));
  CHECK(has(run.err, "'rigid_1_2'"));
  CHECK(has(run.err, "redundant = \"drop\""));
  CHECK_FALSE(std::filesystem::exists(box.path("r.csv")));
}

}  // namespace test_cli_redundant_drop
