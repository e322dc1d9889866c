// Issue 13, items 1 and 2: `condyn run` on a truss shaken by a recorded ground acceleration from a
// CSV file beside the scene, run from another folder; and a bad record's message and exit code.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "tests/cli_sandbox.hpp"

using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

/// A one-bay frame (two supports, two storey masses) in case/, its record in case/records/.
void write_case(const Sandbox& box, const std::string& record) {
  std::filesystem::create_directories(box.path("case/records"));
  box.write("case/records/quake.csv", record);
  box.write("case/s.toml", R"(name = "frame under a record"
[model]
type = "truss2d"
nodes = [[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]
masses = [0.0, 0.0, 1000.0, 1000.0]
supports = [1, 2]
members = [{ nodes = [1, 4], EA = 1e7 }, { nodes = [2, 3], EA = 1e7 },
           { nodes = [3, 4], EA = 1e8 }, { nodes = [1, 3], EA = 1e6 }]
[ground_motion]
direction = "x"
acceleration = { type = "table", file = "records/quake.csv", column = "ag", scale = 9.81 }
[solve]
t_end = 1.0
output_step = 0.5
scheme = "ggl"
)");
}

}  // namespace

TEST_CASE("cli ground motion: a tabulated record shakes a truss, paths from the scene's folder") {
  const Sandbox box;
  write_case(box, "# a short record in g\nt,ag\n0,0\n0.1,0.2\n0.2,-0.1\n0.3,0.05\n");
  const Result r = box.run("run case/s.toml --out r.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string csv = slurp(box.path("r.csv"));
  CHECK(csv.rfind("t,ux1,uy1,ux2,uy2,ux3,uy3,ux4,uy4,drift_position,drift_velocity\n", 0) == 0);
}

TEST_CASE("cli ground motion: a bad record is refused with exit 2, the key, the file and line") {
  const Sandbox box;
  write_case(box, "t,ag\n0,0\n0.1,0.2\n0.1,0.3\n");
  const Result r = box.run("run case/s.toml --out r.csv");
  CHECK(r.code == 2);
  CHECK(r.err.find("case/s.toml:11: ground_motion.acceleration.file: case/records/quake.csv:4: "
                   "the time 0.1 is not after the previous sample's") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(box.path("r.csv")));
}
