// [[derived]] columns end to end (docs/scenes.md, "Derived columns"): models/scenes/
// two_storey_frame.toml's drifts, drift ratio, base shear and storey shear as columns of the
// CSV (streamed to a file, or whole to standard output: the same bytes) and of the HDF5 file,
// bounded by `condyn check`, and bad [[derived]] tables refused before any output is written.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/csv_table.hpp"
#include "tests/hdf5_read.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_derived {

using condyn::test::check_derived_as_csv;
using condyn::test::CsvTable;
using condyn::test::read_csv_table;
using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

const std::string kFrame =
    slurp(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/two_storey_frame.toml");

/// The largest |x| of a column.
double peak(const std::vector<double>& x) {
  double m = 0.0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

/// max over rows of |x − y|, y computed from the row by `expected`.
template <class Expected>
double worst(const CsvTable& table, const std::string& column, const Expected& expected) {
  const auto& x = table.columns.at(column);
  double w = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) w = std::max(w, std::abs(x[k] - expected(k)));
  return w;
}

}  // namespace

TEST_CASE("cli derived: the frame's drifts and base shear are columns equal to their sums") {
  Sandbox box;
  // An inertia force from accelerations that [output] does not show: the run computes them.
  box.write("frame.toml", kFrame +
                              "[[derived]]\nname = \"inertia2\"\nterms = { acc_u2 = "
                              "-20000.0 }\n");
  const Result r = box.run("run frame.toml --out frame.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const CsvTable table = read_csv_table(slurp(box.path("frame.csv")));
  const std::string header =
      "t,base_l,base_r,u1,u2,reaction_base_l,reaction_base_r,reaction_u1,"
      "reaction_u2,drift_position,drift_velocity,drift1,drift2,"
      "drift_ratio2,base_shear,storey_shear2,inertia2";
  std::string joined;
  for (const auto& h : table.header) joined += (joined.empty() ? "" : ",") + h;
  CHECK(joined == header);  // after every quantity's columns; no acceleration column shown
  const auto& c = table.columns;
  const auto at = [&c](const char* name, std::size_t k) { return c.at(name)[k]; };
  REQUIRE(c.at("t").size() == 201);
  // Sums of two terms of coefficient ±1 are the CSV's own differences: roundoff of the sum,
  // 4 eps of the larger term (the columns read back exactly: shortest round-trip digits).
  const double u_scale = std::max(peak(c.at("u1")), peak(c.at("u2")));
  REQUIRE(u_scale > 1e-4);  // the roof moves (about 1e-2 m): the comparison is not of zeros
  CHECK(worst(table, "drift2", [&](std::size_t k) { return at("u2", k) - at("u1", k); }) <=
        4 * kEps * u_scale);
  CHECK(worst(table, "drift1", [&](std::size_t k) { return at("u1", k) - at("base_l", k); }) <=
        4 * kEps * u_scale);
  CHECK(worst(table, "drift_ratio2", [&](std::size_t k) {
          return (at("u2", k) - at("u1", k)) / 3.0;
        }) <= 4 * kEps * u_scale);
  const double r_scale = std::max(peak(c.at("reaction_base_l")), peak(c.at("reaction_base_r")));
  REQUIRE(r_scale > 1e3);
  CHECK(worst(table, "base_shear", [&](std::size_t k) {
          return -(at("reaction_base_l", k) + at("reaction_base_r", k));
        }) <= 4 * kEps * r_scale);
  // A term on an earlier derived column: 1.5e7 · drift2, roundoff of one product.
  CHECK(worst(table, "storey_shear2", [&](std::size_t k) { return 1.5e7 * at("drift2", k); }) <=
        4 * kEps * 1.5e7 * u_scale);
  // Physics: the base shear is the first storey's spring force, 2e7 (u1 − base): the reactions
  // come from the equations at each row (the supports' own inertia is 0, as their acceleration
  // is), and elimination holds the supports exactly, so only roundoff of the few products and
  // sums of 1e5-sized forces separates them: observed 0.56 eps of the shear's peak (2.3e5 N);
  // bound 16 eps of it.
  const double shear_scale = peak(c.at("base_shear"));
  CHECK(worst(table, "base_shear", [&](std::size_t k) { return 2e7 * at("u1", k); }) <=
        16 * kEps * shear_scale);
  // The roof's inertia force −m2 u2'' balances the load less the top storey's shear; the
  // accelerations come from the forces at the row, so only roundoff of the same 1e5-sized
  // forces separates them: observed 0.84 eps of the shear's peak; bound 16 eps of it.
  CHECK(worst(table, "inertia2", [&](std::size_t k) {
          return at("storey_shear2", k) - 1e5 * std::sin(10.0 * at("t", k));
        }) <= 16 * kEps * shear_scale);

  // Whole to standard output (not streamed): the same bytes.
  const Result whole = box.run("run frame.toml --out -");
  REQUIRE(whole.code == 0);
  CHECK(whole.out == slurp(box.path("frame.csv")));
}

TEST_CASE("cli derived: the HDF5 file holds the derived columns and their names") {
  Sandbox box;
  box.write("frame.toml", kFrame);
  REQUIRE(box.run("run frame.toml --out frame.csv").code == 0);
  const Result r = box.run("run frame.toml --out frame.h5");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  // The CSV's columns, each value exactly the CSV's.
  const CsvTable csv = read_csv_table(slurp(box.path("frame.csv")));
  REQUIRE(csv.columns.at("t").size() == 201);
  check_derived_as_csv(box.path("frame.h5").string(), csv,
                       {"drift1", "drift2", "drift_ratio2", "base_shear", "storey_shear2"});
}

TEST_CASE("cli derived: a [[check]] bounds a derived column, passing and failing") {
  Sandbox box;
  box.write("frame.toml", kFrame);
  const Result pass = box.run("check frame.toml");
  CAPTURE(pass.out);
  CHECK(pass.code == 0);
  CHECK(pass.out.find("PASS check[1] drift_ratio2 (max_abs): max |drift_ratio2| = ") !=
        std::string::npos);
  // The same bound on the base shear (about 1e5 N) cannot hold.
  box.write("tight.toml", kFrame + "[[check]]\nquantity = \"base_shear\"\nmax_abs = 1000.0\n");
  const Result fail = box.run("check tight.toml");
  CAPTURE(fail.out);
  CHECK(fail.code == 1);
  CHECK(fail.out.find("PASS check[1] drift_ratio2 (max_abs)") != std::string::npos);
  CHECK(fail.out.find("FAIL check[2] base_shear (max_abs): max |base_shear| = ") !=
        std::string::npos);
}

TEST_CASE("cli derived: bad [[derived]] tables: exit 2 naming file, line, entry, no output") {
  Sandbox box;
  struct Case {
    std::string from, to, message;
  };
  const Case cases[] = {
      // Built: a column the model does not have, with the nearest names.
      {"terms = { u2 = 1.0, u1 = -1.0 }", "terms = { u2 = 1.0, u3 = -1.0 }",
       "derived[2].terms.u3: derived column 'drift2': no output column is named 'u3'"},
      // Read: a later column, a non-finite coefficient.
      {"terms = { u2 = 1.0, u1 = -1.0 }", "terms = { u2 = 1.0, storey_shear2 = -1.0 }",
       "derived[2].terms.storey_shear2: derived column 'drift2': names derived column "
       "'storey_shear2' of derived[5], which comes after it"},
      {"terms = { u2 = 1.0, u1 = -1.0 }", "terms = { u2 = 1.0, u1 = -inf }",
       "derived[2].terms.u1: derived column 'drift2': the coefficient -inf is not finite"},
      {"name = \"drift2\"", "name = \"u2\"",
       "derived[2].name: derived column 'u2': the name is already a displacement column"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.to);
    std::string text = kFrame;
    text.replace(text.find(c.from), c.from.size(), c.to);
    box.write("bad.toml", text);
    const Result r = box.run("run bad.toml --out bad.csv");
    CAPTURE(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.find("bad.toml:") != std::string::npos);
    CHECK(r.err.find(c.message) != std::string::npos);
    CHECK_FALSE(condyn::test::fs::exists(box.path("bad.csv")));
    const Result check = box.run("check bad.toml");  // the same refusal before any run
    CHECK(check.code == 2);
    CHECK(check.out.find(c.message) != std::string::npos);
  }
}

TEST_CASE("cli derived: a mechanism's joint reaction and acceleration columns as terms") {
  // The four-bar's joint O and crank columns, with neither reactions nor accelerations shown:
  // the run computes them for the derived column. The same run showing them is the reference.
  std::string text =
      slurp(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/multibody/four_bar.toml");
  text = condyn::test::replace(text, "t_end = 2.0", "t_end = 0.5");
  const std::string shown = "quantities = [\"displacement\", \"velocity\", \"drift\", \"energy\"]";
  text = condyn::test::replace(text, shown, "quantities = [\"displacement\"]");
  text += "[[derived]]\nname = \"mix\"\nterms = { \"O.fx\" = 1.0, \"crank.ax\" = 0.5 }\n";
  Sandbox box;
  box.write("hidden.toml", text);
  box.write("shown.toml", condyn::test::replace(
                              text, "quantities = [\"displacement\"]",
                              "quantities = [\"displacement\", \"acceleration\", \"reaction\"]"));
  const Result hidden = box.run("run hidden.toml --out hidden.csv");
  CAPTURE(hidden.err);
  REQUIRE(hidden.code == 0);
  REQUIRE(box.run("run shown.toml --out shown.csv").code == 0);
  const CsvTable a = read_csv_table(slurp(box.path("hidden.csv")));
  const CsvTable b = read_csv_table(slurp(box.path("shown.csv")));
  CHECK(a.header.back() == "near_singular");  // the flag stays last, after the derived column
  CHECK(a.header[a.header.size() - 2] == "mix");
  CHECK(a.columns.count("O.fx") == 0);  // not shown
  const auto& mix = a.columns.at("mix");
  const double scale = peak(b.columns.at("O.fx")) + 0.5 * peak(b.columns.at("crank.ax"));
  REQUIRE(scale > 0.0);
  // The same run both times (what is shown changes no step): the sum of the shown columns,
  // to the roundoff of one sum.
  CHECK(worst(b, "mix", [&](std::size_t k) {
          return b.columns.at("O.fx")[k] + 0.5 * b.columns.at("crank.ax")[k];
        }) <= 4 * kEps * scale);
  REQUIRE(mix.size() == b.columns.at("mix").size());
  for (std::size_t k = 0; k < mix.size(); ++k) CHECK(mix[k] == b.columns.at("mix")[k]);
}

TEST_CASE("cli derived: info lists each derived column's formula, expanded as it is computed") {
  Sandbox box;
  box.write("frame.toml", kFrame +
                              "[[derived]]\nname = \"inertia2\"\nterms = { acc_u2 = "
                              "-20000.0 }\n");
  const Result r = box.run("info frame.toml");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("derived columns: 6\n") != std::string::npos);
  CHECK(r.out.find("  drift1 = -base_l + u1\n") != std::string::npos);
  CHECK(r.out.find("  drift_ratio2 = -0.333333 u1 + 0.333333 u2\n") != std::string::npos);
  CHECK(r.out.find("  base_shear = -reaction_base_l - reaction_base_r\n") != std::string::npos);
  // storey_shear2 reads drift2: its terms are drift2's, times 1.5e7.
  CHECK(r.out.find("  storey_shear2 = -1.5e+07 u1 + 1.5e+07 u2\n") != std::string::npos);
  CHECK(r.out.find("  inertia2 = -20000 acc_u2\n") != std::string::npos);
}

}  // namespace test_cli_derived
