// Singular configurations on the command line: `run` names each passage (time, closeness, the
// output rows inside it) in its summary and warns on standard error when a run left its branch;
// `check` carries that warning beside its verdicts.
#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "tests/cli_sandbox.hpp"

namespace {

std::string scene_text(const std::string& name) {
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/" + name);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The N-four-bar run to t = 1.5, past its first horizontal crossings.
std::string short_n_four_bar() {
  std::string text = scene_text("n_four_bar.toml");
  const std::string end = "t_end = 10.0";
  text.replace(text.find(end), end.size(), "t_end = 1.5");
  return text;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("run names the parallelogram's passages near its collinear configuration") {
  condyn::test::Sandbox box;
  box.write("p.toml", scene_text("parallelogram_four_bar.toml"));
  const auto r = box.run("run p.toml --out p.csv");  // GGL: stays on the parallelogram
  REQUIRE(r.code == 0);
  CHECK(has(r.out, "passed 2 near-singular configurations"));
  CHECK(has(r.out, "row t = 1)"));
  CHECK(has(r.out, "row t = 3)"));
  CHECK_FALSE(has(r.err, "left its branch"));
  // index1 takes the crossed branch at t = 3 (tests/dae/test_singular_passages.cpp).
  const auto left = box.run("run p.toml --scheme index1 --out q.csv");
  REQUIRE(left.code == 0);
  CHECK(has(left.err,
            "warning: p.toml: the run left its branch at the singular configuration "
            "near t = 3 "));
  CHECK(has(left.out, "row t = 3, left its branch)"));
}

TEST_CASE("run warns when index2 leaves the N-four-bar's branch, not when projection stays on it") {
  condyn::test::Sandbox box;
  box.write("n.toml", short_n_four_bar());
  const auto left = box.run("run n.toml --scheme index2 --out n.csv");
  CHECK(left.code == 0);  // the run is complete: a warning, not a failure
  CHECK(has(left.err, "warning: n.toml: the run left its branch at the singular configuration"));
  CHECK(has(left.out, "left its branch"));
  const auto kept = box.run("run n.toml --scheme projection --out p.csv");
  CHECK(kept.code == 0);
  CHECK(has(kept.out, "near-singular configuration"));
  CHECK_FALSE(has(kept.err, "left its branch"));
}

TEST_CASE("check prints the change of branch beside its verdicts") {
  condyn::test::Sandbox box;
  box.write("n.toml",
            short_n_four_bar() + "\n[[check]]\nquantity = \"drift_position\"\nmax_abs = 1.0\n");
  const auto r = box.run("check n.toml --scheme index2");
  CHECK(r.code == 0);  // the check itself holds
  CHECK(has(r.out, "warning: the run left its branch"));
}
