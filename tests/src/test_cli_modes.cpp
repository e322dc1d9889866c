// condyn modes end to end: the table's columns and values against the shear building's closed
// form, the mode shapes file, standard output, the HDF5 file (the CSV's table and shapes, the same
// doubles), and bad input (exit 2, the flag or key named, no file written).
#include <doctest/doctest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/hdf5_read.hpp"
#include "tests/scene_text.hpp"
#include "tests/shear_building.hpp"

namespace test_cli_modes {

using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::ShearBuilding;

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

std::vector<std::vector<std::string>> csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream l(line);
    for (std::string cell; std::getline(l, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// The CSV's numbers read back as the doubles written; the dense solver's roundoff on ω² of the
// 4-storey building is a few eps of ω²_max = 4 k/m: 64 eps relative to ω on these O(1) values
// (their smallest is 0.35 of ω_max).
constexpr double kTableTolerance = 1e-13;

}  // namespace

TEST_CASE("modes writes the table of periods and mass ratios, and the shapes") {
  const Sandbox box;
  const ShearBuilding b{.storeys = 4, .mass = 1.0, .stiffness = 40.0, .ground_motion = true};
  box.write("b.toml", condyn::test::shear_building_scene(b));
  const Result r = box.run("modes b.toml --out m.csv --shapes s.csv");
  REQUIRE(r.code == 0);
  CHECK(
      contains(r.out, "4 of 4 modes (dense eigensolver), total mass along the influence vector 4"));
  CHECK(contains(r.out, "wrote the modes to m.csv"));
  const auto rows = csv(condyn::test::slurp(box.path("m.csv")));
  REQUIRE(rows.size() == 5);
  CHECK(rows[0] == std::vector<std::string>{"mode", "omega", "frequency", "period", "mass_ratio",
                                            "mass_ratio_cumulative"});
  const double two_pi = 6.283185307179586;
  for (int j = 1; j <= 4; ++j) {
    const auto& row = rows[static_cast<std::size_t>(j)];
    CHECK(row[0] == std::to_string(j));
    const double omega = condyn::test::shear_building_omega(b, j);
    CHECK(std::abs(std::stod(row[1]) - omega) <= kTableTolerance * omega);
    CHECK(std::abs(std::stod(row[2]) - omega / two_pi) <= kTableTolerance * omega);
    CHECK(std::abs(std::stod(row[3]) - two_pi / omega) <= kTableTolerance * two_pi / omega);
  }
  CHECK(std::abs(std::stod(rows[4][5]) - 1.0) <= kTableTolerance);
  const auto shapes = csv(condyn::test::slurp(box.path("s.csv")));
  REQUIRE(shapes.size() == 5);
  CHECK(shapes[0] == std::vector<std::string>{"dof", "mode_1", "mode_2", "mode_3", "mode_4"});
  CHECK(shapes[4][0] == "u4");
  // The first mode: every storey moves the same way, the top most (largest entry positive).
  for (int i = 1; i <= 4; ++i) CHECK(std::stod(shapes[static_cast<std::size_t>(i)][1]) > 0.0);

  // Without --out: the CSV alone on standard output, the summary on standard error; no ratio
  // columns without [ground_motion].
  ShearBuilding plain = b;
  plain.ground_motion = false;
  box.write("p.toml", condyn::test::shear_building_scene(plain));
  const Result p = box.run("modes p.toml --count 2");
  REQUIRE(p.code == 0);
  const auto out = csv(p.out);
  REQUIRE(out.size() == 3);
  CHECK(out[0] == std::vector<std::string>{"mode", "omega", "frequency", "period"});
  CHECK(contains(p.err, "2 of 4 modes"));
}

TEST_CASE("modes gives a rigid motion a zero frequency and an infinite period") {
  const Sandbox box;
  // Two unit masses on a spring of stiffness 2, nothing holding them: ω = 0 and ω = 2.
  box.write("free.toml",
            "[model]\ntype = \"matrix\"\ndofs = [\"a\", \"b\"]\nmass = [[1.0, 0.0], [0.0, "
            "1.0]]\nstiffness = [[2.0, -2.0], [-2.0, 2.0]]\n[solve]\nt_end = 1.0\noutput_step = "
            "0.5\n");
  const Result r = box.run("modes free.toml");
  REQUIRE(r.code == 0);
  const auto rows = csv(r.out);
  REQUIRE(rows.size() == 3);
  CHECK(rows[1] == std::vector<std::string>{"1", "0", "0", "inf"});
  CHECK(std::abs(std::stod(rows[2][1]) - 2.0) <= kTableTolerance * 2.0);
  // The HDF5 file holds the infinite period as it is.
  REQUIRE(box.run("modes free.toml --out free.h5").code == 0);
  const hid_t file = H5Fopen(box.path("free.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const auto period = condyn::test::read_doubles(file, "period").values;
  REQUIRE(period.size() == 2);
  CHECK(std::isinf(period[0]));
  CHECK(period[0] > 0.0);
  H5Fclose(file);
}

TEST_CASE("modes --out FILE.h5 holds the CSV's table and shapes, the same doubles") {
  const Sandbox box;
  const ShearBuilding b{.storeys = 4, .mass = 1.0, .stiffness = 40.0, .ground_motion = true};
  box.write("b.toml", condyn::test::shear_building_scene(b));
  REQUIRE(box.run("modes b.toml --out m.csv --shapes s.csv").code == 0);
  const Result r = box.run("modes b.toml --count 3 --out m.h5");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(contains(r.out, "wrote the modes and their shapes to m.h5"));
  const auto table = csv(condyn::test::slurp(box.path("m.csv")));
  const auto shapes = csv(condyn::test::slurp(box.path("s.csv")));
  const hid_t file = H5Fopen(box.path("m.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  // One dataset per column of the table, three modes of the CSV's four: the CSV's shortest
  // round-trip numbers read back as the very doubles the HDF5 file holds.
  CHECK(condyn::test::stored_class(file, "mode") == H5T_INTEGER);
  const char* columns[] = {"mode",   "omega",      "frequency",
                           "period", "mass_ratio", "mass_ratio_cumulative"};
  for (std::size_t c = 0; c < 6; ++c) {
    CAPTURE(columns[c]);
    CHECK(table[0][c] == columns[c]);
    const condyn::test::Dataset d = condyn::test::read_doubles(file, columns[c]);
    REQUIRE(d.dims == std::vector<hsize_t>{3});
    for (std::size_t j = 0; j < 3; ++j) CHECK(d.values[j] == std::stod(table[j + 1][c]));
  }
  // The shapes: n x K, row i the DOF dof_names[i], as the shapes CSV's rows.
  const condyn::test::Dataset phi = condyn::test::read_doubles(file, "shapes");
  REQUIRE(phi.dims == std::vector<hsize_t>{4, 3});
  const auto names = condyn::test::read_strings(file, "dof_names");
  REQUIRE(names.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(names[i] == shapes[i + 1][0]);
    for (std::size_t j = 0; j < 3; ++j)
      CHECK(phi.values[3 * i + j] == std::stod(shapes[i + 1][j + 1]));
  }
  CHECK(condyn::test::read_string_attribute(file, "solver") == "dense");
  CHECK(condyn::test::read_attribute(file, "available") == 4.0);
  // The storeys' mass, 4 x 1, to the roundoff of the effective masses' sum (kTableTolerance).
  CHECK(std::abs(condyn::test::read_attribute(file, "total_mass") - 4.0) <= kTableTolerance * 4.0);
  H5Fclose(file);

  // Without [ground_motion]: no mass ratios, no total mass, as the CSV has no such columns.
  ShearBuilding plain = b;
  plain.ground_motion = false;
  box.write("p.toml", condyn::test::shear_building_scene(plain));
  REQUIRE(box.run("modes p.toml --out p.H5").code == 0);  // the extension in any case
  const hid_t p = H5Fopen(box.path("p.H5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(p >= 0);
  CHECK(H5Lexists(p, "omega", H5P_DEFAULT) > 0);
  CHECK(H5Lexists(p, "mass_ratio", H5P_DEFAULT) == 0);
  CHECK(H5Lexists(p, "mass_ratio_cumulative", H5P_DEFAULT) == 0);
  CHECK(H5Aexists(p, "total_mass") == 0);
  H5Fclose(p);
}

TEST_CASE("modes refuses bad input with exit 2, naming the flag or key, writing nothing") {
  const Sandbox box;
  box.write("b.toml", condyn::test::shear_building_scene(ShearBuilding{.storeys = 3}));
  ShearBuilding massless{.storeys = 3};
  massless.mass_scale = 0.0;
  box.write("z.toml", condyn::test::shear_building_scene(massless));
  box.write("p.toml", condyn::test::pendulum_scene("t_end = 1.0\noutput_step = 0.5\n"));
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"modes b.toml --count 0 --out m.csv", "--count: '0' is not a whole number"},
      {"modes b.toml --count -1 --out m.csv", "--count"},
      {"modes b.toml --count 2.5 --out m.csv", "--count: '2.5' is not a whole number"},
      {"modes b.toml --count 4 --out m.csv",
       "b.toml: --count: must be from 1 to the number of modes of the constrained model, 3 (3 "
       "DOFs, 0 constraints); got 4"},
      {"modes z.toml --out m.csv", "z.toml: model.mass: the model has no mass"},
      {"modes p.toml --out m.csv", "p.toml: model: natural modes need a linear model"},
      {"modes b.toml --out m.txt",
       "--out m.txt: the extension .txt names no format condyn writes: --out writes CSV (.csv, or "
       "a name without an extension) or HDF5 (.h5, .hdf5, .hdf)"},
      {"modes b.toml --out m.csv --shapes s.txt", "--shapes"},
      {"modes b.toml --out m.csv --shapes s.h5", "--shapes s.h5: the extension .h5"},
      {"modes b.toml --out b.toml", "--out"},
      {"modes b.toml --out missing/m.h5", "--out missing/m.h5: the folder"},
      {"modes b.toml --out m.h5 --count 4", "--count: must be from 1"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.args);
    const Result r = box.run(c.args);
    CHECK(r.code == 2);
    CHECK(contains(r.err, c.says));
    CHECK_FALSE(std::filesystem::exists(box.path("m.csv")));
    CHECK_FALSE(std::filesystem::exists(box.path("m.h5")));
  }
  CHECK(condyn::test::slurp(box.path("b.toml")) ==
        condyn::test::shear_building_scene(ShearBuilding{.storeys = 3}));
  // A protected file under an HDF5 name: refused before the solve, kept as it was.
  box.write("old.h5", "kept\n");
  std::filesystem::permissions(box.path("old.h5"), std::filesystem::perms::owner_read);
  const Result kept = box.run("modes b.toml --out old.h5");
  CHECK(kept.code == 2);
  CHECK(contains(kept.err, "--out old.h5"));
  CHECK(contains(kept.err, "is read-only"));
  CHECK(condyn::test::slurp(box.path("old.h5")) == "kept\n");
}

}  // namespace test_cli_modes
