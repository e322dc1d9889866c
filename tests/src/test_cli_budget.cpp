// A run's budget ([solve] max_steps, max_wall_time; run --max-steps, --max-wall-time): exceeding
// it is a failed run (exit 1) with its kind, its advice and its partial result; bad values are
// refused naming the key. Load steps at ordinary times through the command line.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_budget {

using namespace condyn::test;

namespace {

std::string pendulum(const std::string& solve_keys) {
  return condyn::test::pendulum_scene("scheme = \"ggl\"\n" + solve_keys);
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("run: a step budget ends a long run with its kind, advice and partial result") {
  const Sandbox box;
  // The pendulum to t_end = 1e5: ordinary steps, each output interval well inside the
  // per-interval limit; only a budget stops it.
  box.write("p.toml", pendulum("t_end = 1e5\noutput_step = 1.0\nmax_steps = 5000\n"));
  const Result r = box.run("run p.toml --out out.csv");
  CAPTURE(r.err);
  CHECK(r.code == 1);
  CHECK(contains(r.err, "(step budget exhausted)"));
  CHECK(contains(r.err, "took more than 5000 steps in all"));
  CHECK(contains(r.err, "suggestion: the run used up its step budget"));
  CHECK(contains(r.err, "out.partial.csv"));
  CHECK_FALSE(contains(r.err, "collapsed"));
  CHECK_FALSE(fs::exists(box.path("out.csv")));
  const std::string partial = slurp(box.path("out.partial.csv"));
  CHECK(std::count(partial.begin(), partial.end(), '\n') > 2);  // header, t = 0 and later rows
  // The time in the budget's message is the time reached the report gives: the step that used
  // up the budget succeeded (they differed by one step).
  const auto number_after = [&](const std::string& key) {
    const auto at = r.err.find(key);
    REQUIRE(at != std::string::npos);
    const auto from = at + key.size();
    return r.err.substr(from, r.err.find_first_of(",)", from) - from);
  };
  CHECK(number_after("steps in all (at t = ") ==
        number_after("reached t = ").substr(0, number_after("reached t = ").find(' ')));

  // --max-steps overrides the scene's budget.
  const Result flag = box.run("run p.toml --max-steps 300 --out out.csv");
  CHECK(flag.code == 1);
  CHECK(contains(flag.err, "took more than 300 steps in all"));
  // Leading zeros are decimal: CLI11 read "0300" as octal (192 steps) and refused "08".
  for (const char* padded : {"0300", "+000300"}) {
    CAPTURE(padded);
    const Result zeros =
        box.run("run p.toml --max-steps " + std::string(padded) + " --out out.csv");
    CHECK(zeros.code == 1);
    CHECK(contains(zeros.err, "took more than 300 steps in all"));
  }
  const Result eight = box.run("run p.toml --max-steps 08 --out out.csv");
  CHECK(eight.code == 1);
  CHECK(contains(eight.err, "took more than 8 steps in all"));

  // A budget spent before the second output time: the row at t = 0 is kept all the same, and
  // replaces the partial file of the failure before.
  box.write("q.toml", pendulum("t_end = 10.0\noutput_step = 5.0\n"));
  const Result early = box.run("run q.toml --max-steps 5 --out out.csv");
  CHECK(early.code == 1);
  CHECK(contains(early.err, "partial result: the output row at t = 0 is in out.partial.csv"));
  const std::string one_row = slurp(box.path("out.partial.csv"));
  CHECK(std::count(one_row.begin(), one_row.end(), '\n') == 2);  // header and t = 0
  CHECK(one_row.find("\n0,") != std::string::npos);
}

TEST_CASE("run: [solve] max_steps_per_output is a budget of its own, named in the failure") {
  const Sandbox box;
  // GGL on the pendulum takes more than 40 steps to reach t = 5, its only output after 0.
  box.write("p.toml", pendulum("t_end = 5.0\noutput_step = 5.0\nmax_steps_per_output = 40\n"));
  const Result r = box.run("run p.toml --out out.csv");
  CAPTURE(r.err);
  CHECK(r.code == 1);
  CHECK(contains(r.err, "(too many steps between two outputs)"));
  CHECK(contains(r.err, "took 40 steps without reaching the output time 5"));
  CHECK(contains(r.err, "the budget of steps between two outputs, [solve] max_steps_per_output"));
  CHECK(contains(r.err, "a larger [solve] max_steps_per_output (default 100000"));
  CHECK(contains(r.err, "out.partial.csv"));
  // A budget that suffices lets the same run through.
  box.write("p.toml", pendulum("t_end = 5.0\noutput_step = 5.0\nmax_steps_per_output = 1e6\n"));
  const Result ok = box.run("run p.toml --out out.csv");
  CAPTURE(ok.err);
  CHECK(ok.code == 0);
}

TEST_CASE("run: a wall-time budget ends the run as a failure with its kind") {
  const Sandbox box;
  box.write("p.toml", pendulum("t_end = 1e5\noutput_step = 1.0\n"));
  // The smallest budget the flag accepts: over after the first step, whatever the machine.
  const Result r = box.run("run p.toml --max-wall-time 1e-9 --out out.csv");
  CAPTURE(r.err);
  CHECK(r.code == 1);
  CHECK(contains(r.err, "(wall-time budget exhausted)"));
  CHECK(contains(r.err, "suggestion: the run used up its wall-time budget"));
}

TEST_CASE("run: bad budgets are refused, naming the key or flag") {
  const Sandbox box;
  const std::pair<const char*, const char*> bad_keys[] = {
      {"max_steps = 0", "solve.max_steps"},
      {"max_steps = -5", "solve.max_steps"},
      {"max_steps = 2.5", "solve.max_steps"},
      {"max_steps = \"many\"", "solve.max_steps"},
      {"max_wall_time = 0.0", "solve.max_wall_time"},
      {"max_wall_time = -1", "solve.max_wall_time"},
      {"max_wall_time = inf", "solve.max_wall_time"},
      {"max_wall_time = nan", "solve.max_wall_time"},
      {"max_steps_per_output = 0", "solve.max_steps_per_output"},
      {"max_steps_per_output = -5", "solve.max_steps_per_output"},
      {"max_steps_per_output = 2.5", "solve.max_steps_per_output"},
      {"max_steps_per_output = 1e19", "solve.max_steps_per_output"},
      {"max_steps_per_output = \"many\"", "solve.max_steps_per_output"},
  };
  for (const auto& bad : bad_keys) {
    // Named copies: clang 14 cannot capture structured bindings in CAPTURE's lambda.
    const std::string line = bad.first, key = bad.second;
    CAPTURE(line);
    box.write("p.toml", pendulum(std::string("t_end = 1.0\noutput_step = 0.1\n") + line + "\n"));
    const Result r = box.run("run p.toml --out out.csv");
    CAPTURE(r.err);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "p.toml"));
    CHECK(contains(r.err, key));
  }
  box.write("p.toml", pendulum("t_end = 1.0\noutput_step = 0.1\n"));
  for (const char* args : {"--max-steps 0", "--max-steps -3", "--max-steps 1.5",
                           "--max-wall-time 0", "--max-wall-time -2", "--max-wall-time x"}) {
    CAPTURE(args);
    const Result r = box.run(std::string("run p.toml --out out.csv ") + args);
    CAPTURE(r.err);
    CHECK(r.code == 2);
    CHECK(contains(r.err, std::string(args).substr(0, std::string(args).find(' '))));
  }
  // A budget written as 1e6 is a whole number: accepted, and a short run stays inside it.
  box.write("p.toml", pendulum("t_end = 1.0\noutput_step = 0.1\nmax_steps = 1e6\n"));
  const Result ok = box.run("run p.toml --out out.csv");
  CAPTURE(ok.err);
  CHECK(ok.code == 0);
  CHECK(ok.err.find("progress:") == std::string::npos);  // a short run prints no progress
}

TEST_CASE("run: a failure at t = 0 is explained as a failure to start, not a singular motion") {
  const Sandbox box;
  // 15 digits with atol 1e-30: GGL's error test fails at every trial of its first step.
  box.write("p.toml", pendulum("t_end = 10.0\noutput_step = 0.1\nrtol = 1e-15\natol = 1e-30\n"));
  const Result r = box.run("run p.toml --out out.csv");
  CAPTURE(r.err);
  CHECK(r.code == 1);
  CHECK(contains(r.err, "(failure before the first step)"));
  CHECK(contains(r.err, "suggestion: the integrator failed before its first step"));
  CHECK_FALSE(contains(r.err, "singular configuration"));
  CHECK_FALSE(contains(r.err, "collapsed"));
}

TEST_CASE("run: a load step at 0.3 with output_step 0.1 runs, its row at 0.3") {
  const Sandbox box;
  box.write("s.toml", R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 2.0]]
[[load]]
dof = "a"
value = { type = "step", start = 0.3 }
[[constraint]]
terms = { a = 1.0, b = -1.0 }
[solve]
t_end = 1.0
output_step = 0.1
)");
  for (const char* scheme : {"elimination", "ggl", "projection"}) {
    CAPTURE(scheme);
    const Result r = box.run(std::string("run s.toml --out out.csv --scheme ") + scheme);
    CAPTURE(r.err);
    CHECK(r.code == 0);
    const std::string csv = slurp(box.path("out.csv"));
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 11);
    // The load step's time, as written: 0.3 (CSV numbers are the shortest form that reads back as
    // the same double; 3 x 0.1 would read 0.30000000000000004).
    CHECK(contains(csv, "\n0.3,"));
  }
}

}  // namespace test_cli_budget
