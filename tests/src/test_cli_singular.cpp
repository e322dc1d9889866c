// Singular configurations on the command line: `run` names each passage (time, closeness, the
// output rows inside it) in its summary and warns on standard error when a run left its branch;
// `check` carries that warning beside its verdicts.
#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"

namespace test_cli_singular {

namespace {

std::string scene_text(const std::string& name) {
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/" + name);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A scene whose schemes take their own steps through singular configurations: no bridge.
std::string unbridged(std::string text) {
  const std::string solve = "[solve]\n";
  text.replace(text.find(solve), solve.size(), solve + "bridge_singular = false\n");
  return text;
}

/// The N-four-bar run to t = 1.5, past its first horizontal crossings, without bridges.
std::string short_n_four_bar() {
  std::string text = scene_text("n_four_bar.toml");
  const std::string end = "t_end = 10.0";
  text.replace(text.find(end), end.size(), "t_end = 1.5");
  return unbridged(text);
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A CSV's header's last column, and the `t` of the rows whose last field is "1".
struct Flags {
  std::string last_column;
  std::vector<std::string> flagged;
};

Flags flags_of(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  Flags f;
  std::getline(in, line);
  f.last_column = line.substr(line.rfind(',') + 1);
  while (std::getline(in, line)) {
    if (line.substr(line.rfind(',') + 1) == "1")
      f.flagged.push_back(line.substr(0, line.find(',')));
  }
  return f;
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
  // Bridged (the default), index1 holds the branch; by its own steps it takes the crossed one
  // at t = 3 (tests/dae/test_singular_passages.cpp).
  const auto bridged = box.run("run p.toml --scheme index1 --out b.csv");
  REQUIRE(bridged.code == 0);
  CHECK(has(bridged.out, "bridged 2 near-singular configurations with generalized-α steps"));
  CHECK_FALSE(has(bridged.err, "left its branch"));
  box.write("p.toml", unbridged(scene_text("parallelogram_four_bar.toml")));
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

TEST_CASE("the result flags the rows inside a passage in a last column near_singular") {
  condyn::test::Sandbox box;
  const std::string scene = scene_text("parallelogram_four_bar.toml");  // writes reactions
  box.write("p.toml", scene);
  // Streamed to a file, and whole to standard output: the same rows, those the summary names
  // (its passages at t = 1 and t = 3 each hold one output row).
  const auto streamed = box.run("run p.toml --out p.csv");
  REQUIRE(streamed.code == 0);
  REQUIRE(has(streamed.out, "row t = 1)"));
  REQUIRE(has(streamed.out, "row t = 3)"));
  const Flags file = flags_of(condyn::test::slurp(box.path("p.csv")));
  CHECK(file.last_column == "near_singular");
  CHECK(file.flagged == std::vector<std::string>{"1", "3"});
  const auto whole = box.run("run p.toml --out -");
  REQUIRE(whole.code == 0);
  const Flags out = flags_of(whole.out);
  CHECK(out.last_column == "near_singular");
  CHECK(out.flagged == file.flagged);
  // No column where nothing it flags is written, nor for a constant constraint Jacobian.
  std::string no_reactions = scene;
  const std::string asked = R"(quantities = ["displacement", "velocity", "reaction", "drift"])";
  REQUIRE(has(no_reactions, asked));
  no_reactions.replace(no_reactions.find(asked), asked.size(),
                       R"(quantities = ["displacement", "drift"])");
  box.write("q.toml", no_reactions);
  REQUIRE(box.run("run q.toml --out q.csv").code == 0);
  CHECK(flags_of(condyn::test::slurp(box.path("q.csv"))).last_column == "drift_velocity");
  box.write("linear.toml", scene_text("truss_inclined_roller.toml"));  // writes reactions
  REQUIRE(box.run("run linear.toml --out linear.csv").code == 0);
  CHECK(flags_of(condyn::test::slurp(box.path("linear.csv"))).last_column == "drift_velocity");
}

}  // namespace test_cli_singular
