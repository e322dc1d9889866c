// What `condyn validate` prints about its published-benchmark requirements is read by users: it
// states the requirement and where it comes from, never a figure observed on some earlier build
// (those went stale: "observed 8.73" while validate printed 8.70) nor an internal reference (an
// issue number, a path into files users do not have).
#include <doctest/doctest.h>

#include <regex>
#include <string>

#include "validation/references/benchmark_suite.hpp"

namespace test_published_case_texts {

TEST_CASE("published-benchmark requirement texts carry no stale figures or internal references") {
  const std::regex stale(R"(observed|issue\s*[0-9]|shared/|item\s*[0-9])", std::regex::icase);
  REQUIRE_FALSE(condyn::published_cases().empty());
  for (const condyn::PublishedCase& c : condyn::published_cases()) {
    CAPTURE(c.scene);
    CAPTURE(c.reason);
    CHECK_FALSE(c.reason.empty());
    CHECK_FALSE(std::regex_search(c.reason, stale));
  }
}

}  // namespace test_published_case_texts
