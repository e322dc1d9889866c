// [[derived]] columns on absolute accelerations (docs/scenes.md, "Derived columns"): under
// [ground_motion], acc_abs_ terms are u'' + r a_g(t) at the row, the acc_abs_ columns' values:
// models/scenes/shear_frame_el_centro.toml's base shear from the inertia forces and a floor's
// absolute acceleration as columns (CSV streamed and whole, HDF5), listed by info, bounded by
// check; on models/scenes/two_storey_frame.toml shaken by the record, the inertia base shear is
// minus the support reactions' sum; without [ground_motion] an acc_abs_ term is refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/csv_table.hpp"
#include "tests/hdf5_read.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_derived_absolute {

using condyn::test::check_derived_as_csv;
using condyn::test::CsvTable;
using condyn::test::read_csv_table;
using condyn::test::replace;
using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

const std::string kScenes = std::string(CONDYN_SOURCE_DIR) + "/models/scenes/";
const std::string kRecord = "file = \"" + kScenes + "data/el_centro_1940_ns.csv\"";

using Terms = std::vector<std::pair<std::string, double>>;

/// The largest, over the rows, of |column − Σ c·x| in units of the row's roundoff bound for a
/// sum of `terms.size()` products: n eps Σ|c·x| (recursive summation errs by at most (n − 1)
/// eps/2 of it, the products by eps/2 each), times `scale` (the column's own coefficient, 1 if
/// none). At most 1 when the column is the combination of the CSV's columns to roundoff.
double worst_in_roundoff(const CsvTable& table, const std::string& column, const Terms& terms,
                         double scale = 1.0) {
  const auto& x = table.columns.at(column);
  double worst = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    double sum = 0.0, size = 0.0;
    for (const auto& [name, c] : terms) {
      sum += c * table.columns.at(name)[k];
      size += std::abs(c * table.columns.at(name)[k]);
    }
    const double bound = static_cast<double>(terms.size() + 1) * kEps * size * scale;
    worst = std::max(worst, std::abs(x[k] - scale * sum) / std::max(bound, kEps));
  }
  return worst;
}

/// shear_frame_el_centro.toml over the record's first 2 s, showing `quantities` for every DOF,
/// with a base shear (the inertia forces −m (u'' + r a_g) summed over the ten DOFs of 1e5 kg), the
/// roof's absolute acceleration (its two DOFs' mean), the shear in kN (a derived column on a
/// derived one) and a check on the roof.
std::string frame(const std::string& quantities) {
  std::string text = slurp(kScenes + "shear_frame_el_centro.toml");
  text = replace(text, "file = \"data/el_centro_1940_ns.csv\"", kRecord);
  text = replace(text, "t_end = 31.16", "t_end = 2.0");
  text = replace(text, "quantities = [\"displacement\", \"reaction\", \"drift\"]\ndofs = [\"ul*\"]",
                 "quantities = " + quantities);
  std::string shear;
  for (int floor = 1; floor <= 5; ++floor) {
    for (const char* side : {"ul", "ur"}) {
      shear += std::string(shear.empty() ? "" : ", ") + "acc_abs_" + side + std::to_string(floor) +
               " = -1e5";
    }
  }
  return text + "[[derived]]\nname = \"base_shear\"\nterms = { " + shear +
         " }\n[[derived]]\nname = \"roof_abs\"\nterms = { acc_abs_ul5 = 0.5, acc_abs_ur5 = 0.5 }\n"
         "[[derived]]\nname = \"base_shear_kN\"\nterms = { base_shear = 0.001 }\n"
         "[[check]]\nquantity = \"roof_abs\"\nmax_abs = 100.0\n";
}

}  // namespace

TEST_CASE("cli derived absolute: a base shear and a floor's acceleration from acc_abs_ columns") {
  Sandbox box;
  box.write("frame.toml", frame("[\"absolute_acceleration\"]"));
  const Result r = box.run("run frame.toml --out frame.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const CsvTable table = read_csv_table(slurp(box.path("frame.csv")));
  CHECK(table.header_line().rfind("t,acc_abs_ul1,acc_abs_ur1,", 0) == 0);
  CHECK(table.header_line().find(",acc_abs_ur5,base_shear,roof_abs,base_shear_kN") !=
        std::string::npos);
  REQUIRE(table.columns.at("t").size() == 101);
  Terms shear;
  for (const auto& [name, x] : table.columns) {
    if (name.rfind("acc_abs_", 0) == 0) shear.emplace_back(name, -1e5);
  }
  REQUIRE(shear.size() == 10);
  // The record shakes the frame: the roof's absolute acceleration is of the order of a_g
  // (El Centro's first 2 s peak near 0.3 g), not a comparison of zeros.
  double roof = 0.0;
  for (double x : table.columns.at("roof_abs")) roof = std::max(roof, std::abs(x));
  CHECK(roof > 1.0);
  CHECK(worst_in_roundoff(table, "base_shear", shear) <= 1.0);
  CHECK(worst_in_roundoff(table, "roof_abs", {{"acc_abs_ul5", 0.5}, {"acc_abs_ur5", 0.5}}) <= 1.0);
  // The kN column's terms are base_shear's times 0.001 (the builder expands them), so it is the
  // same sum times 0.001, one more rounding of the coefficients.
  CHECK(worst_in_roundoff(table, "base_shear_kN", shear, 0.001) <= 1.0);

  // Whole to standard output (not streamed), and without the acc_abs_ columns shown: the same
  // run, the same derived values.
  const Result whole = box.run("run frame.toml --out -");
  REQUIRE(whole.code == 0);
  CHECK(whole.out == slurp(box.path("frame.csv")));
  box.write("hidden.toml", frame("[\"displacement\"]"));
  REQUIRE(box.run("run hidden.toml --out hidden.csv").code == 0);
  const CsvTable hidden = read_csv_table(slurp(box.path("hidden.csv")));
  CHECK(hidden.columns.count("acc_abs_ul1") == 0);
  for (const char* name : {"base_shear", "roof_abs", "base_shear_kN"}) {
    CHECK(hidden.columns.at(name) == table.columns.at(name));
  }

  // HDF5 (streamed row by row): each value exactly the CSV's.
  REQUIRE(box.run("run frame.toml --out frame.h5").code == 0);
  check_derived_as_csv(box.path("frame.h5").string(), table,
                       {"base_shear", "roof_abs", "base_shear_kN"});

  // info lists the formulas with their acc_abs_ terms; check bounds the floor's acceleration.
  const Result info = box.run("info frame.toml");
  CAPTURE(info.out);
  REQUIRE(info.code == 0);
  CHECK(info.out.find("  roof_abs = 0.5 acc_abs_ul5 + 0.5 acc_abs_ur5\n") != std::string::npos);
  CHECK(info.out.find("  base_shear_kN = -100 acc_abs_ul1 - 100 acc_abs_ul2") != std::string::npos);
  const Result pass = box.run("check frame.toml");
  CAPTURE(pass.out);
  CHECK(pass.code == 0);
  CHECK(pass.out.find("PASS check[1] roof_abs (max_abs): max |roof_abs| = ") != std::string::npos);
  box.write("tight.toml",
            replace(slurp(box.path("frame.toml")), "max_abs = 100.0", "max_abs = 0.01"));
  const Result fail = box.run("check tight.toml");
  CHECK(fail.code == 1);
  CHECK(fail.out.find("FAIL check[1] roof_abs (max_abs)") != std::string::npos);
}

TEST_CASE("cli derived absolute: the inertia base shear is minus the support reactions' sum") {
  // two_storey_frame.toml without its roof load, shaken by the record (r = 1 on every DOF, the
  // supports' too). With f_con the reactions, M u'' + K u = −M r a_g + f_con, K's rows sum to 0
  // (a rigid translation strains no spring) and there is no damping: Σ m (u'' + r a_g) = Σ f_con
  // at every row. The frame's base_shear is −Σ f_con; `inertia` is −Σ m (u'' + r a_g).
  std::string text = slurp(kScenes + "two_storey_frame.toml");
  text = replace(text,
                 "[[load]]\ndof = \"u2\"\nvalue = { type = \"harmonic\", amplitude = 1.0e5, "
                 "omega = 10.0 }\n",
                 "[ground_motion]\nacceleration = { type = \"table\", " + kRecord +
                     ", scale = 9.81 }\ninfluence = { base_l = 1.0, base_r = 1.0, u1 = 1.0, "
                     "u2 = 1.0 }\n");
  text +=
      "[[derived]]\nname = \"inertia\"\nterms = { acc_abs_base_l = -1000.0, acc_abs_base_r = "
      "-1000.0, acc_abs_u1 = -20000.0, acc_abs_u2 = -20000.0 }\n"
      "[[derived]]\nname = \"imbalance\"\nterms = { inertia = 1.0, base_shear = -1.0 }\n";
  Sandbox box;
  box.write("frame.toml", text);
  const Result r = box.run("run frame.toml --out frame.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const CsvTable table = read_csv_table(slurp(box.path("frame.csv")));
  double shear = 0.0, imbalance = 0.0;
  for (double x : table.columns.at("base_shear")) shear = std::max(shear, std::abs(x));
  for (double x : table.columns.at("imbalance")) imbalance = std::max(imbalance, std::abs(x));
  REQUIRE(shear > 1e4);  // 4.2e4 kg under El Centro's first 2 s: tens of kN
  // Only roundoff separates them: the reactions are recovered from the equations at the row
  // and the accelerations solved from the same forces, sums of forces up to the springs'
  // k |u| ~ shear. Observed 1.3 eps of the shear's peak; bound 16 eps of it.
  CHECK(imbalance <= 16 * kEps * shear);
}

TEST_CASE("cli derived absolute: an acc_abs_ term without [ground_motion] is refused, exit 2") {
  Sandbox box;
  box.write("frame.toml", slurp(kScenes + "two_storey_frame.toml") +
                              "[[derived]]\nname = \"inertia2\"\nterms = { acc_abs_u2 = -2e4 }\n");
  const std::string message =
      "derived[6].terms.acc_abs_u2: derived column 'inertia2': 'acc_abs_u2' needs "
      "[ground_motion]: without a moving ground the absolute acceleration is the acceleration "
      "(name acc_u2)";
  const Result r = box.run("run frame.toml --out frame.csv");
  CAPTURE(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.find("frame.toml:") != std::string::npos);
  CHECK(r.err.find(message) != std::string::npos);
  CHECK_FALSE(condyn::test::fs::exists(box.path("frame.csv")));
  for (const char* command : {"check frame.toml", "info frame.toml"}) {
    const Result refused = box.run(command);
    CAPTURE(command);
    CHECK(refused.code == 2);
    CHECK((refused.out + refused.err).find(message) != std::string::npos);
  }
}

}  // namespace test_cli_derived_absolute
