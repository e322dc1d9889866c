// Mechanisms on the command line (docs/scenes.md, "Mechanisms of rigid bodies"): the example
// scenes run under every scheme that applies, `info` lists each joint's rows, and a start that
// violates a joint is refused with exit 2, naming it, with nothing written.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>

#include "tests/cli_sandbox.hpp"

namespace test_cli_multibody {

namespace {

std::string scene_text(const std::string& name) {
  std::ifstream in(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/multibody/" + name);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// `text` with its first `from` replaced by `to` (which must be there).
std::string edited(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("the slider-crank runs under every multiplier scheme and projection") {
  condyn::test::Sandbox box;
  box.write("s.toml", scene_text("slider_crank.toml"));
  for (const std::string scheme :
       {"auto", "index1", "baumgarte", "ggl", "index2", "index3", "projection"}) {
    CAPTURE(scheme);
    const auto r = box.run("run s.toml --scheme " + scheme + " --out s_" + scheme + ".csv");
    CAPTURE(r.err);
    CHECK(r.code == 0);
    CHECK(has(r.out, "projected the bodies' start onto the joints"));
  }
}

TEST_CASE("the spatial four-bar and the pendulum run, and info lists each joint's rows") {
  condyn::test::Sandbox box;
  box.write("f.toml", scene_text("spatial_four_bar.toml"));
  const auto run = box.run("run f.toml --out f.csv");
  CAPTURE(run.err);
  CHECK(run.code == 0);
  const auto info = box.run("info f.toml");
  CHECK(info.code == 0);
  CHECK(has(info.out, "joint: A (spherical, crank - coupler): 3 rows"));
  CHECK(has(info.out, "holonomic, scleronomic"));
  box.write("p.toml", scene_text("pendulum_a01.toml"));
  const auto pendulum = box.run("run p.toml --out p.csv");
  CAPTURE(pendulum.err);
  CHECK(pendulum.code == 0);
}

TEST_CASE("a start violating a joint is refused with exit 2, naming it, nothing is written") {
  condyn::test::Sandbox box;
  const std::string text =
      edited(scene_text("four_bar.toml"), "position = [0.4, 0.1]", "position = [0.41, 0.1]");
  box.write("bad.toml", text);
  const auto r = box.run("run bad.toml --out bad.csv");
  CHECK(r.code == 2);
  CHECK(has(r.err, "bad.toml:"));
  CHECK(has(r.err, "the initial poses violate joint"));
  CHECK_FALSE(condyn::test::fs::exists(box.path("bad.csv")));
}

namespace {

/// Three equal cranks hanging from the ground under one coupler: a parallelogram with a redundant
/// crank (1 degree of freedom, 12 rows of rank 11), at rest in its stable equilibrium.
std::string hanging_three_cranks() {
  std::string s =
      "[model]\ntype = \"multibody\"\ndimension = 2\ngravity = [0.0, -9.81]\n"
      "ground = { O1 = [0.0, 0.0], O2 = [1.0, 0.0], O3 = [2.0, 0.0] }\n"
      "[[body]]\nname = \"coupler\"\nmass = 1.0\ninertia = 0.3\nposition = [1.0, -1.0]\n"
      "points = { A1 = [-1.0, 0.0], A2 = [0.0, 0.0], A3 = [1.0, 0.0] }\n";
  for (int k = 1; k <= 3; ++k) {
    const std::string n = std::to_string(k);
    s += "[[body]]\nname = \"crank" + n + "\"\nmass = 1.0\ninertia = 0.08\nposition = [" +
         std::to_string(k - 1) + ".0, -0.5]\nangle = -1.5707963267948966\n" +
         "points = { top = [-0.5, 0.0], bottom = [0.5, 0.0] }\n";
    s += "[[joint]]\nname = \"O" + n + "\"\ntype = \"revolute\"\nbodies = [\"ground\", \"crank" +
         n + "\"]\npoints = [\"O" + n + "\", \"top\"]\n";
    s += "[[joint]]\nname = \"A" + n + "\"\ntype = \"revolute\"\nbodies = [\"crank" + n +
         "\", \"coupler\"]\npoints = [\"bottom\", \"A" + n + "\"]\n";
  }
  return s + "[solve]\nt_end = 0.1\noutput_step = 0.05\nredundant = \"drop\"\n" +
         "[output]\nquantities = [\"reaction\"]\n";
}

/// The values of the CSV's last row by column name.
std::map<std::string, double> last_row(const std::string& csv) {
  std::istringstream in(csv);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::map<std::string, double> row;
  std::istringstream names(header), values(last);
  std::string name, value;
  while (std::getline(names, name, ',') && std::getline(values, value, ','))
    row[name] = std::stod(value);
  return row;
}

}  // namespace

TEST_CASE("a dropped redundant joint row: the reactions of the kept rows carry the weight") {
  // At rest in equilibrium the ground's three hinges hold the four bodies' weight, 4 m g, however
  // the redundant set shares it (not unique); every kept multiplier must reach its own joint's
  // columns (the output map reads rows in the full system's numbering).
  condyn::test::Sandbox box;
  const auto dir = box.write("h.toml", hanging_three_cranks()).parent_path();
  const auto r = box.run("run h.toml --scheme ggl --out h.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(has(r.out, "dropped redundant constraint"));
  const auto row = last_row(condyn::test::slurp(dir / "h.csv"));
  const double weight = 4.0 * 9.81;
  const double held = row.at("O1.fy") + row.at("O2.fy") + row.at("O3.fy");
  // The equilibrium is exact at t = 0 and the rows hold to rtol (1e-6 by default).
  CHECK(std::abs(held - weight) <= 1e-6 * weight);
  CHECK(std::abs(row.at("O1.fx") + row.at("O2.fx") + row.at("O3.fx")) <= 1e-6 * weight);
}

}  // namespace test_cli_multibody
