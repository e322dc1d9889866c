// Issue 47 item 8: support motion from the command line. The two-support bridge example passes its
// checks against the exact response; a truss support moved by an accelerogram integrated twice
// follows it (total displacements); bad records exit 2 naming the key, the file and the line.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "tests/cli_sandbox.hpp"

namespace test_cli_support_motion {

using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

const std::string kSource = CONDYN_SOURCE_DIR;

/// A bar from a supported node 1 to node 2 (mass 1, EA/L = 100), node 2's y held; node 1's x is
/// moved by `value`, its y fixed.
std::string truss_scene(const std::string& value, double t_end = 1.0) {
  std::ostringstream s;
  s << R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
members = [{ nodes = [1, 2], EA = 100.0 }]
[[constraint]]
name = "shake"
terms = { ux1 = 1.0 }
value = )"
    << value << R"(
[[constraint]]
terms = { uy1 = 1.0 }
[[constraint]]
terms = { uy2 = 1.0 }
[solve]
t_end = )"
    << t_end << R"(
output_step = 0.5
scheme = "ggl"
rtol = 1e-10
atol = 1e-14
[output]
quantities = ["displacement", "reaction"]
)";
  return s.str();
}

/// The value in column `name` of the CSV's last row.
double last_value(const std::string& csv, const std::string& name) {
  std::istringstream in(csv);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  std::istringstream h(header), row(last);
  std::string cell, value;
  while (std::getline(h, cell, ',') && std::getline(row, value, ',')) {
    if (cell == name) return std::stod(value);
  }
  FAIL("no column " << name);
  return 0.0;
}

}  // namespace

TEST_CASE(
    "cli support motion: the two-support bridge passes its checks against the exact response") {
  const Sandbox box;
  const Result r = box.run("check '" + kSource + "/models/scenes/two_support_bridge.toml'");
  CAPTURE(r.out);
  CAPTURE(r.err);
  CHECK(r.code == 0);
  CHECK(r.out.find("reaction_sR") != std::string::npos);
}

TEST_CASE("cli support motion: an accelerogram integrated twice moves a truss support") {
  const Sandbox box;
  // a = 6t on [0, 1]: v = 3t², d = t³ (integrated exactly: the record is linear), no baseline.
  box.write("acc.csv", "t,a\n0,0\n1,6\n");
  box.write(
      "s.toml",
      truss_scene(
          R"({ type = "displacement_record", file = "acc.csv", acceleration = "a", baseline = "none" })"));
  const Result r = box.run("run s.toml --out r.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string csv = slurp(box.path("r.csv"));
  // The support's displacement is total: d(1) = 1, to the constraint's roundoff.
  CHECK(last_value(csv, "ux1") == doctest::Approx(1.0).epsilon(1e-12));
  // The support drives the bar: its reaction is nonzero and the node follows.
  CHECK(last_value(csv, "reaction_ux1") != 0.0);
  CHECK(last_value(csv, "ux2") > 0.0);
}

TEST_CASE("cli support motion: a mechanism's drive given as a record triple runs as its function") {
  // The slider-crank's drive 2πt, sampled as a record triple (d = 2πt, v = 2π, a = 0 every
  // 0.1 s), which the quintic Hermite reproduces exactly: the two runs agree within their
  // integration error (rtol 1e-8 of the scene on positions of order 0.1 m: 1e-7 is 10³ rtol of
  // the slider's travel).
  const Sandbox box;
  std::string scene = slurp(kSource + "/models/scenes/multibody/slider_crank.toml");
  const std::string drive =
      R"(drive = { type = "polynomial", coefficients = [0.0, 6.283185307179586] })";
  REQUIRE(scene.find(drive) != std::string::npos);
  box.write("orig.toml", scene);
  std::ostringstream crank;
  crank.precision(17);
  crank << "t,d,v,a\n";
  for (int k = 0; k <= 10; ++k) {
    crank << 0.1 * k << "," << 2.0 * 3.141592653589793 * 0.1 * k << "," << 2.0 * 3.141592653589793
          << ",0\n";
  }
  box.write("crank.csv", crank.str());
  scene.replace(
      scene.find(drive), drive.size(),
      R"(drive = { type = "displacement_record", file = "crank.csv", displacement = "d", velocity = "v", acceleration = "a" })");
  box.write("rec.toml", scene);
  REQUIRE(box.run("run orig.toml --out o.csv").code == 0);
  const Result r = box.run("run rec.toml --out r.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string o = slurp(box.path("o.csv")), c = slurp(box.path("r.csv"));
  REQUIRE(o.substr(0, o.find('\n')) == c.substr(0, c.find('\n')));
  std::istringstream header(o.substr(0, o.find('\n')));
  int columns = 0;
  for (std::string cell; std::getline(header, cell, ',');) {
    if (cell.find(".x") == std::string::npos && cell.find(".y") == std::string::npos) continue;
    ++columns;
    CAPTURE(cell);
    CHECK(std::abs(last_value(o, cell) - last_value(c, cell)) <= 1e-7);
  }
  CHECK(columns > 0);
}

TEST_CASE("cli support motion: bad records exit 2 naming the key, the file and the line") {
  const Sandbox box;
  box.write("d.csv", "t,d,v,a\n0,0,0,0\n1,1,1,0\n1,2,0,0\n");
  box.write(
      "s.toml",
      truss_scene(
          R"({ type = "displacement_record", file = "d.csv", displacement = "d", velocity = "v", acceleration = "a" })"));
  Result r = box.run("run s.toml --out r.csv");
  CAPTURE(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.find("constraint[1].value") != std::string::npos);
  CHECK(r.err.find("d.csv:4: the time 1 is not after") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(box.path("r.csv")));

  box.write("s.toml",
            truss_scene(R"({ type = "displacement_record", file = "d.csv", displacement = "d" })"));
  r = box.run("run s.toml");
  CHECK(r.code == 2);
  CHECK(r.err.find("a displacement record needs either") != std::string::npos);
}

}  // namespace test_cli_support_motion
