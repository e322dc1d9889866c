// [solve] linear_solver from the command line (issue 47, item 1): `info` reports the factorization
// and each candidate's analysis, `run` says which factorization it used, and the refusals (an
// unknown value, "cholmod" where the Newton matrix is a saddle point) exit 2 naming the key and
// write nothing.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/lattice_scene.hpp"

namespace test_cli_linear_solver {

using condyn::test::Result;
using condyn::test::Sandbox;

namespace {

/// A 12 x 12 lattice with a tie, under `solve_keys`.
std::string lattice_scene(const std::string& solve_keys) {
  return condyn::test::lattice(
      12, 12,
      "[[constraint]]\nname = \"tie\"\nterms = { uy144 = 1.0, uy133 = -1.0 }\n"
      "[[load]]\ndof = \"uy144\"\nvalue = { type = \"step\", amplitude = -1.0 }\n",
      solve_keys);
}

}  // namespace

TEST_CASE("info and run report CHOLMOD's analysis and use under elimination") {
  Sandbox box;
  box.write("s.toml", lattice_scene("scheme = \"elimination\"\nlinear_solver = \"cholmod\"\n"));
  const Result info = box.run("info s.toml");
  REQUIRE(info.code == 0);
  CHECK(info.out.find("factorization: CHOLMOD (") != std::string::npos);
  for (const char* candidate :
       {"KLU (amd)", "CHOLMOD (amd)", "CHOLMOD (metis)", "CHOLMOD (nesdis)"}) {
    CAPTURE(candidate);
    CHECK(info.out.find(candidate) != std::string::npos);
  }
  // The memory line (wrapped: its lines joined here) counts CHOLMOD's factor, which the run will
  // hold.
  std::string joined;
  for (std::size_t i = 0; i < info.out.size(); ++i) {
    if (info.out[i] != '\n') {
      joined += info.out[i];
      continue;
    }
    joined += ' ';
    while (i + 1 < info.out.size() && info.out[i + 1] == ' ') ++i;
  }
  CHECK(joined.find("CHOLMOD's factor predicted at") != std::string::npos);
  const Result run = box.run("run s.toml --out r.csv");
  REQUIRE(run.code == 0);
  CHECK((run.out + run.err).find("CHOLMOD (") != std::string::npos);
  // KLU named: info still gives the candidates of the condensed matrix, the run says nothing of
  // CHOLMOD.
  box.write("k.toml", lattice_scene("scheme = \"elimination\"\nlinear_solver = \"klu\"\n"));
  const Result klu = box.run("info k.toml");
  REQUIRE(klu.code == 0);
  CHECK(klu.out.find("factorization: KLU ([solve] linear_solver = \"klu\"); its condensed") !=
        std::string::npos);
  CHECK(klu.out.find("CHOLMOD (nesdis)") != std::string::npos);
}

TEST_CASE("linear_solver refusals exit 2 naming the key and write nothing") {
  Sandbox box;
  box.write("bad.toml", lattice_scene("linear_solver = \"mumps\"\n"));
  const Result bad = box.run("run bad.toml --out r.csv");
  CHECK(bad.code == 2);
  CHECK(bad.err.find("solve.linear_solver: expected 'auto', 'klu', 'cholmod' or 'dense'") !=
        std::string::npos);
  box.write("ggl.toml", lattice_scene("scheme = \"ggl\"\nlinear_solver = \"cholmod\"\n"));
  for (const char* command : {"run ggl.toml --out r.csv", "info ggl.toml"}) {
    CAPTURE(command);
    const Result ggl = box.run(command);
    CHECK(ggl.code == 2);
    CHECK(ggl.err.find("ggl.toml:") != std::string::npos);
    CHECK(ggl.err.find("solve.linear_solver: \"cholmod\" cannot factor") != std::string::npos);
    CHECK(ggl.err.find("not symmetric positive definite") != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(box.path("r.csv")));
}

}  // namespace test_cli_linear_solver
