// Issue 13, items 1 and 2: `condyn run` on a truss shaken by a recorded ground acceleration from a
// CSV file beside the scene, run from another folder; and a bad record's message and exit code.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_ground_motion {

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

TEST_CASE("cli ground motion: info shows the record and the loads' time functions") {
  const Sandbox box;
  write_case(box, "t,ag\n0,0\n0.1,0.2\n0.2,-0.1\n");
  const Result r = box.run("info case/s.toml");
  CAPTURE(r.out);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("ground motion: a_g(t) = table(records/quake.csv:ag, 3 samples)*9.81") !=
        std::string::npos);
  CHECK(r.out.find("loads: 1\n  pattern (") != std::string::npos);
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

TEST_CASE("cli ground motion: absolute accelerations are the relative ones plus r a_g(t)") {
  // Output every 0.05 s over a record sampled every 0.1 s (in g, scale 9.81): at each row,
  // acc_abs_ux = acc_ux + a_g(t) on the x DOFs (r = 1) and acc_abs_uy = acc_uy; a_g interpolated
  // linearly between the samples (0.05 s: (0 + 0.2)/2 g).
  const Sandbox box;
  write_case(box, "t,ag\n0,0\n0.1,0.2\n0.2,-0.1\n0.3,0.05\n");
  const std::string scene = slurp(box.path("case/s.toml"));
  box.write("case/a.toml",
            condyn::test::replace(scene, "output_step = 0.5\n", "output_step = 0.05\n") +
                "[output]\nquantities = [\"acceleration\", \"absolute_acceleration\"]\n"
                "dofs = [\"ux3\", \"uy3\"]\n");
  const Result r = box.run("run case/a.toml --out a.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  std::istringstream in(slurp(box.path("a.csv")));
  std::string line;
  std::getline(in, line);
  CHECK(line == "t,acc_ux3,acc_uy3,acc_abs_ux3,acc_abs_uy3");
  const auto ag = [](double t) {  // the record, m/s², constant after its last sample
    const double ts[] = {0.0, 0.1, 0.2, 0.3}, g[] = {0.0, 0.2, -0.1, 0.05};
    if (t >= 0.3) return 0.05 * 9.81;
    const int k = static_cast<int>(t / 0.1 + 1e-9);
    const double s = (t - ts[k]) / 0.1;
    return 9.81 * (g[k] + s * (g[k + 1] - g[k]));
  };
  int rows = 0;
  double largest = 0.0;
  while (std::getline(in, line)) {
    double t = 0, ax = 0, ay = 0, abs_x = 0, abs_y = 0;
    char c = 0;
    std::istringstream row(line);
    row >> t >> c >> ax >> c >> ay >> c >> abs_x >> c >> abs_y;
    CAPTURE(line);
    CHECK(abs_x - ax == doctest::Approx(ag(t)).epsilon(1e-12).scale(1.0));
    CHECK(abs_y == ay);
    largest = std::max(largest, std::abs(ax));
    ++rows;
  }
  CHECK(rows == 21);
  CHECK(largest > 0.1);  // the frame moves relative to the ground: the two columns differ

  // Without [ground_motion] the quantity is refused: the accelerations are absolute already.
  box.write("case/b.toml",
            "[model]\ntype = \"matrix\"\ndofs = [\"x\"]\nmass = [[1.0]]\n"
            "stiffness = [[1.0]]\n[solve]\nt_end = 1.0\noutput_step = 0.5\n"
            "[output]\nquantities = [\"absolute_acceleration\"]\n");
  const Result b = box.run("run case/b.toml --out b.csv");
  CHECK(b.code == 2);
  CHECK(b.err.find("b.toml:10: output.quantities: 'absolute_acceleration' needs [ground_motion]") !=
        std::string::npos);
}

}  // namespace test_cli_ground_motion
