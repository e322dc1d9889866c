// Issue 10, item 23: `info` lists the DOFs a nonlinear constraint depends on structurally, and
// keeps long DOF lists (hundreds of masters) within 100 columns.
#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_info_dofs {

using condyn::test::Result;
using condyn::test::Sandbox;

namespace {

std::string source(const std::string& path) {
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) + "/" + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Report lines stay within this width (docs/cli.md, `condyn info`).
constexpr std::size_t kWidth = 100;

}  // namespace

TEST_CASE("info: the sleigh's knife edge depends on x, y and theta") {
  Sandbox box;
  // theta(0) = 0: the x coefficient -sin(theta) is 0 there, yet the row depends on x.
  box.write("sleigh.toml", source("models/scenes/chaplygin_sleigh.toml"));
  const Result r = box.run("info sleigh.toml");
  REQUIRE(r.code == 0);
  const auto row = r.out.find("knife_edge");
  REQUIRE(row != std::string::npos);
  const std::string line = r.out.substr(row, r.out.find('\n', row) - row);
  CHECK(line.find("x, y, theta") != std::string::npos);
}

TEST_CASE("info: hundreds of masters print no line over 100 characters") {
  // A chain of 300 nodes (600 DOFs), node 1 pinned: 598 masters under elimination.
  std::string nodes, masses, members;
  for (int k = 0; k < 300; ++k) {
    nodes += (k ? ", [" : "[") + std::to_string(k) + ".0, 0.0]";
    masses += k ? ", 1.0" : "1.0";
    if (k) {
      members += (k > 1 ? ", { nodes = [" : "{ nodes = [") + std::to_string(k) + ", " +
                 std::to_string(k + 1) + "], EA = 1.0 }";
    }
  }
  Sandbox box;
  box.write("chain.toml", "[model]\ntype = \"truss2d\"\nnodes = [" + nodes + "]\nmasses = [" +
                              masses + "]\nmembers = [" + members +
                              "]\nsupports = [1]\n[solve]\nt_end = 1.0\noutput_step = 0.5\n"
                              "scheme = \"elimination\"\n");
  const Result r = box.run("info chain.toml");
  REQUIRE(r.code == 0);
  CHECK(r.out.find("2 slaves (chosen by column pivoting on A), 598 masters") != std::string::npos);
  CHECK(r.out.find("more (598 in all)") != std::string::npos);
  std::istringstream lines(r.out);
  std::size_t longest = 0;
  for (std::string line; std::getline(lines, line);) longest = std::max(longest, line.size());
  CHECK(longest <= kWidth);
}

TEST_CASE("info: DOF lists of nonlinear rows are what the rows use, not the stored pattern") {
  // Andrews and the car axis store their small Jacobian blocks dense (explicit zeros), so the
  // pattern alone would list every DOF; values at u0 alone missed the car axle's yl, yr (their
  // coefficients are zero there).
  const auto row_of = [](const std::string& out, const std::string& name) {
    // A table row starts a line: "  NAME  SFC|MFC ...".
    const auto at = out.find("\n  " + name + " ") + 1;
    REQUIRE(at != 0);
    return out.substr(at, out.find('\n', at) - at);
  };
  Sandbox box;
  const Result andrews =
      box.run("info '" + std::string(CONDYN_SOURCE_DIR) + "/models/scenes/andrews.toml'");
  REQUIRE(andrews.code == 0);
  const std::string g1 = row_of(andrews.out, "g1");
  CHECK(g1.substr(g1.size() - 19) == " beta, Theta, gamma");
  const Result car =
      box.run("info '" + std::string(CONDYN_SOURCE_DIR) + "/models/scenes/car_axis.toml'");
  REQUIRE(car.code == 0);
  const std::string axle = row_of(car.out, "axle");
  CHECK(axle.substr(axle.size() - 15) == " xl, yl, xr, yr");
}

TEST_CASE("info: massless DOFs held by stiffness are named, within 100 columns") {
  Sandbox box;
  box.write("t.toml", condyn::test::kMasslessTriangleScene);
  const Result r = box.run("info t.toml");
  REQUIRE(r.code == 0);
  CHECK(r.out.find("massless DOFs: 2 of 6 (ux3, uy3): 2 held by their stiffness alone "
                   "(algebraic, no inertia)") != std::string::npos);
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) CHECK(line.size() <= kWidth);
}

TEST_CASE("info: above 60 constraints, the first 40 rows and a count per class") {
  // A 70 x 2 lattice, its left column supported (4 SFC), tied top to bottom in columns 2 to 70
  // (69 MFC): 73 constraints.
  std::string extra;
  for (int i = 2; i <= 70; ++i) {
    extra += "[[constraint]]\nname = \"tie" + std::to_string(i) + "\"\nterms = { uy" +
             std::to_string(70 + i) + " = 1.0, uy" + std::to_string(i) + " = -1.0 }\n";
  }
  Sandbox box;
  box.write("ties.toml", condyn::test::lattice(70, 2, extra, "scheme = \"ggl\"\n"));
  const Result r = box.run("info ties.toml");
  REQUIRE(r.code == 0);
  // The supports come first (s1 to s4), then the ties: tie37 is row 40, tie38 row 41.
  CHECK(r.out.find("tie37 ") != std::string::npos);
  CHECK(r.out.find("tie38 ") == std::string::npos);
  CHECK(r.out.find("... and 33 more (73 in all; info --all-constraints lists every one)") !=
        std::string::npos);
  const auto count_line = [&r](const std::string& count, const std::string& kind) {
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
      std::istringstream words(line);
      std::string first, second;
      words >> first >> second;
      if (first == count && second == kind) return line;
    }
    return std::string();
  };
  const std::string mfc = count_line("69", "MFC");
  const std::string sfc = count_line("4", "SFC");
  CHECK(mfc.find("holonomic") != std::string::npos);
  CHECK(mfc.find("linear") != std::string::npos);
  CHECK(sfc.find("homogeneous") != std::string::npos);
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) CHECK(line.size() <= kWidth);

  const Result all = box.run("info ties.toml --all-constraints");
  REQUIRE(all.code == 0);
  CHECK(all.out.find("tie70 ") != std::string::npos);
  CHECK(all.out.find("more (73 in all") == std::string::npos);
}

}  // namespace test_cli_info_dofs
