// [solve] max_order: the highest BDF order IDA and CVODE may use (issue 13, "High frequencies").

#include <doctest/doctest.h>

#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_max_order {

TEST_CASE("max_order caps the BDF order of every scheme's integrator, and the run says so") {
  for (const char* scheme : {"elimination", "index1", "projection"}) {
    CAPTURE(scheme);
    const auto free_order = test::built(parse_scene_text(
        test::stiff_pair_scene(std::string("scheme = \"") + scheme + "\"\n"), "pair.toml"));
    const SolveResult unlimited = test::solved(free_order.model, free_order.spec.solve);
    CHECK(unlimited.summary.max_order_used > 2);  // BDF climbs on the smooth soft mode
    CHECK(unlimited.summary.notes_text().find("BDF order") == std::string::npos);
    for (int cap : {1, 2}) {
      CAPTURE(cap);
      const auto capped = test::built(
          parse_scene_text(test::stiff_pair_scene(std::string("scheme = \"") + scheme +
                                                  "\"\nmax_order = " + std::to_string(cap) + "\n"),
                           "pair.toml"));
      const SolveResult r = test::solved(capped.model, capped.spec.solve);
      CHECK(r.summary.max_order_used >= 1);
      CHECK(r.summary.max_order_used <= cap);
      CHECK(r.summary.notes_text().find("BDF order at most " + std::to_string(cap)) !=
            std::string::npos);
    }
  }
}

TEST_CASE("max_order outside 1..5 is refused naming the key") {
  for (const char* bad : {"0", "6", "2.5", "\"two\""}) {
    CAPTURE(bad);
    CHECK_THROWS_WITH_AS(
        (void)parse_scene_text(test::stiff_pair_scene(std::string("max_order = ") + bad + "\n"),
                               "pair.toml"),
        doctest::Contains("solve.max_order"), SceneError);
  }
}

}  // namespace test_max_order
