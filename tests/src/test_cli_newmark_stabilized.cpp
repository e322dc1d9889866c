// The Newmark family stabilized at index 2 from the command line ([solve] newmark_constraints):
// `run` writes the same columns with the velocity drift at Newton's tolerance where index 3
// leaves O(h²), `info` sizes it, the drift log (--steps-out) and `compare`'s drift columns show
// both forms, and a bad value exits 2 naming the key.
#include <doctest/doctest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_newmark_stabilized {

using condyn::test::Result;
using condyn::test::Sandbox;

namespace {

std::string pendulum(const std::string& solve_keys) {
  return condyn::test::pendulum_scene(R"(t_end = 0.5
output_step = 0.05
step = 0.01
scheme = "generalized_alpha"
rtol = 1e-10
atol = 1e-12
)" + solve_keys) +
         R"([output]
quantities = ["displacement", "velocity", "reaction", "drift"]
)";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// The largest value of the CSV column `name` (a header line, then numbers).
double column_max(const std::string& csv, const std::string& name) {
  std::istringstream in(csv);
  std::string line, cell;
  std::getline(in, line);
  std::istringstream header(line);
  int index = -1;
  for (int i = 0; std::getline(header, cell, ','); ++i) {
    if (cell == name) index = i;
  }
  REQUIRE(index >= 0);
  double largest = 0.0;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (int i = 0; std::getline(row, cell, ','); ++i) {
      if (i == index) largest = std::max(largest, std::stod(cell));
    }
  }
  return largest;
}

/// A velocity drift the stabilized form stays under at h = 0.01, rtol 1e-10: γ' (rtol |u| +
/// atol) with γ' = γ/(hβ) ≈ 200 and |u| ≤ 1 (tests/dae/test_newmark_stabilized.cpp says why).
constexpr double kStabilizedDrift = 200.0 * (1e-10 + 1e-12);
/// Index 3's velocity drift on this pendulum at h = 0.01 is 6.8e-4 (docs/schemes.md); any
/// value above 1e-6 shows it left drifting.
constexpr double kIndex3Drift = 1e-6;

}  // namespace

TEST_CASE("newmark_constraints = stabilized holds the velocity drift in run's columns and log") {
  const Sandbox box;
  box.write("i.toml", pendulum(""));
  box.write("s.toml", pendulum("newmark_constraints = \"stabilized\"\n"));
  const Result i = box.run("run i.toml --out i.csv --steps-out id.csv");
  const Result s = box.run("run s.toml --out s.csv --steps-out sd.csv");
  REQUIRE(i.code == 0);
  REQUIRE(s.code == 0);
  CHECK(contains(s.out + s.err, "constraints stabilized"));
  // info sizes the stabilized system, [u; v; λ; μ]: 2 x 4 + 3 + 3 position rows.
  const Result info = box.run("info s.toml");
  REQUIRE(info.code == 0);
  const auto unknowns_of = [&info](const std::string& name) {
    const std::size_t row = info.out.find("\n  " + name + " ");
    std::string count;
    if (row != std::string::npos)
      std::istringstream(info.out.substr(row + 3 + name.size())) >> count;
    return count;
  };
  CHECK(unknowns_of("generalized_alpha stabilized") == "14");
  // And mixed (the support eliminated): [q; w; λ; μ], 2 x 2 + 1 + 1.
  CHECK(unknowns_of("generalized_alpha mixed stabilized") == "6");
  // The table's columns line up under their heads, the first as wide as its longest name (that
  // name overflowed the 17 characters the column had).
  const auto column_of = [&](const std::string& line_start, const char* field) {
    const std::size_t line = info.out.find("\n" + line_start);
    REQUIRE(line != std::string::npos);
    return info.out.find_first_of(field, line + 1) - (line + 1);
  };
  const std::size_t unknowns = column_of("  scheme ", "u");
  CHECK(column_of("  generalized_alpha stabilized", "0123456789") == unknowns);
  CHECK(column_of("  ggl ", "0123456789") == unknowns);
  const std::string i_csv = condyn::test::slurp(box.path("i.csv"));
  const std::string s_csv = condyn::test::slurp(box.path("s.csv"));
  CHECK(i_csv.substr(0, i_csv.find('\n')) == s_csv.substr(0, s_csv.find('\n')));
  CHECK(column_max(s_csv, "drift_velocity") <= kStabilizedDrift);
  CHECK(column_max(i_csv, "drift_velocity") >= kIndex3Drift);
  const std::string i_log = condyn::test::slurp(box.path("id.csv"));
  const std::string s_log = condyn::test::slurp(box.path("sd.csv"));
  CHECK(column_max(s_log, "drift_velocity") <= kStabilizedDrift);
  CHECK(column_max(i_log, "drift_velocity") >= kIndex3Drift);
}

TEST_CASE("compare reports the drift of both Newmark constraint forms") {
  const Sandbox box;
  box.write("i.toml", pendulum(""));
  box.write("s.toml", pendulum("newmark_constraints = \"stabilized\"\n"));
  for (const char* form : {"i", "s"}) {
    CAPTURE(form);
    const std::string dir = std::string(form) + "-out";
    const Result r =
        box.run(std::string("compare ") + form +
                ".toml --schemes generalized_alpha --tolerances 1e-10 --drift-rtol 1e-10 "
                "--repeats 1 --no-plots --out-dir " +
                dir);
    REQUIRE(r.code == 0);
    const std::string runs = condyn::test::slurp(box.path(dir + "/runs.csv"));
    const std::string log = condyn::test::slurp(box.path(dir + "/drift_generalized_alpha.csv"));
    if (std::string(form) == "s") {
      CHECK(column_max(runs, "max_drift_velocity") <= kStabilizedDrift);
      CHECK(column_max(log, "drift_velocity") <= kStabilizedDrift);
    } else {
      CHECK(column_max(runs, "max_drift_velocity") >= kIndex3Drift);
      CHECK(column_max(log, "drift_velocity") >= kIndex3Drift);
    }
  }
}

TEST_CASE("a bad newmark_constraints exits 2 naming the key") {
  const Sandbox box;
  box.write("b.toml", pendulum("newmark_constraints = \"ggl\"\n"));
  const Result r = box.run("run b.toml --out b.csv");
  CHECK(r.code == 2);
  CHECK(contains(r.err, "b.toml:15: solve.newmark_constraints: expected 'index3'"));
}

}  // namespace test_cli_newmark_stabilized
