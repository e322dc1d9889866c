// compare's mark of runs far beyond their tolerance (OVER in the table, over_tolerance in
// runs.csv) and --fail-above, which makes such runs an exit 1 for CI.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli_sandbox.hpp"

namespace test_cli_compare_marks {

using namespace condyn::test;

TEST_CASE("compare: runs far beyond their target are marked, and --fail-above fails them") {
  const Sandbox box;
  // §5.6.2 (built in) under penalty: its reactions ring at the penalty springs' frequency, 0.11
  // of their size at any rtol (docs/schemes.md), 1.1e3 times penalty's target 1e-4; GGL's worst
  // error at rtol 1e-8 is 40 times rtol (compare on the scene). A factor of 100 lies between.
  const std::string sweep =
      "compare '" + std::string(CONDYN_SOURCE_DIR) +
      "/validation/scenes/chapter_5_6_2.toml' --tolerances 1e-8 --repeats 1 --schemes "
      "ggl,penalty --no-plots --out-dir out";
  const Result marked = box.run(sweep + " --fail-above 100");
  CAPTURE(marked.out);
  CAPTURE(marked.err);
  CHECK(marked.code == 1);
  CHECK(
      marked.err.find("1 run of the comparison missed the target by more than --fail-above 100") !=
      std::string::npos);
  const std::string runs = slurp(box.path("out/runs.csv"));
  CHECK(runs.find(",error_target,error_ratio,over_tolerance\n") != std::string::npos);
  CHECK(runs.find("\nggl,1e-08,") != std::string::npos);
  // The penalty row ends in its target 1e-4, its ratio and the mark 1; GGL's in 0.
  const auto row_end = [&](const std::string& scheme) {
    const auto at = runs.find("\n" + scheme + ",");
    REQUIRE(at != std::string::npos);
    const auto end = runs.find('\n', at + 1);
    return runs.substr(end - 2, 2);
  };
  CHECK(row_end("penalty") == ",1");
  CHECK(row_end("ggl") == ",0");
  CHECK(marked.out.find("OVER") != std::string::npos);

  // Without --fail-above the default factor 1e4 marks neither, and the exit is 0.
  const Result plain = box.run(sweep);
  CAPTURE(plain.err);
  CHECK(plain.code == 0);
  CHECK(slurp(box.path("out/runs.csv")).find(",1\n") == std::string::npos);
  CHECK(box.run(sweep + " --fail-above 0.5").code == 2);  // a factor below 1 is refused
}

}  // namespace test_cli_compare_marks
