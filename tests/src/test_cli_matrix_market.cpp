// Issue 12, item 4: `condyn run` and `condyn info` on a scene whose matrices, constraint block and
// load pattern come from Matrix Market files beside it (scene-format.md, "Matrices and vectors
// from files"), run from another folder; and a bad file's message and exit code.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "tests/cli_sandbox.hpp"

namespace test_cli_matrix_market {

using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

/// A three-DOF chain in case/, its files in case/mats/: u1 held by the block, a pattern load.
void write_case(const Sandbox& box) {
  std::filesystem::create_directories(box.path("case/mats"));
  box.write("case/mats/M.mtx",
            "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1.0\n2 2 1.0\n3 3 1.0\n");
  box.write("case/mats/K.mtx",
            "%%MatrixMarket matrix coordinate real symmetric\n"
            "3 3 5\n1 1 2.0\n2 1 -1.0\n2 2 2.0\n3 2 -1.0\n3 3 1.0\n");
  box.write("case/mats/A.mtx", "%%MatrixMarket matrix coordinate real general\n1 3 1\n1 1 1.0\n");
  box.write("case/mats/f.mtx", "%%MatrixMarket matrix coordinate real general\n3 1 1\n3 1 1.0\n");
  box.write("case/s.toml", R"(name = "chain from files"
[model]
type = "matrix"
mass = { file = "mats/M.mtx" }
stiffness = { file = "mats/K.mtx" }
damping = { rayleigh = [0.0, 0.1] }
[[constraint_block]]
file = "mats/A.mtx"
name = "hold"
[[load]]
pattern = { file = "mats/f.mtx" }
value = { type = "step", amplitude = 1.0 }
[solve]
t_end = 1.0
output_step = 0.5
[output]
quantities = ["displacement", "multiplier"]
)");
}

}  // namespace

TEST_CASE("cli matrix market: run and info on a scene with .mtx files, from another folder") {
  const Sandbox box;
  write_case(box);
  const Result r = box.run("run case/s.toml --out r.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string csv = slurp(box.path("r.csv"));
  CHECK(csv.rfind("t,u1,u2,u3,lambda_hold1\n", 0) == 0);
  const Result info = box.run("info case/s.toml");
  CAPTURE(info.err);
  REQUIRE(info.code == 0);
  CHECK(info.out.find("hold1") != std::string::npos);
}

TEST_CASE("cli matrix market: a bad file is refused with exit 2, naming scene, key, file, line") {
  const Sandbox box;
  write_case(box);
  box.write("case/mats/K.mtx", "%%MatrixMarket matrix coordinate real symmetric\n3 3 1\n1 4 2.0\n");
  for (const char* command : {"run case/s.toml --out r.csv", "info case/s.toml"}) {
    const Result r = box.run(command);
    CAPTURE(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.find("case/s.toml:5: model.stiffness.file: ") != std::string::npos);
    CHECK(r.err.find("mats/K.mtx:3: the index (1, 4) lies outside the 3 x 3 matrix") !=
          std::string::npos);
    CHECK_FALSE(std::filesystem::exists(box.path("r.csv")));
  }
}

}  // namespace test_cli_matrix_market
