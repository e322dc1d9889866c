// `--out FILE.h5` writes the contract's HDF5 layout; its numbers are the CSV's, bit for bit.

#include <doctest/doctest.h>
#include <hdf5.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/hdf5_read.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_hdf5 {

using namespace condyn::test;

namespace {

/// The CSV's rows as numbers (header dropped).
std::vector<std::vector<double>> csv_rows(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("run --out FILE.h5: datasets, names and attributes of the contract, the CSV's numbers") {
  const Sandbox box;
  box.write("s.toml", replace(kTwoMassesScene, "output_step = 0.25\n",
                              "output_step = 0.25\nrtol = 1e-7\n[output]\nquantities = "
                              "[\"displacement\", \"multiplier\", \"drift\"]\ndofs = [\"b\"]\n"));
  const Result h5 = box.run("run s.toml --out out.h5");
  CAPTURE(h5.err);
  REQUIRE(h5.code == 0);
  const Result csv = box.run("run s.toml --out out.csv");
  REQUIRE(csv.code == 0);
  const auto rows = csv_rows(slurp(box.path("out.csv")));  // t, b, lambda_tie, drift x 2
  REQUIRE(rows.size() == 5);

  const hid_t file = H5Fopen(box.path("out.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const Dataset t = read_doubles(file, "t");
  const Dataset u = read_doubles(file, "displacement");
  const Dataset lambda = read_doubles(file, "multiplier");
  const Dataset drift = read_doubles(file, "drift");
  CHECK(t.dims == std::vector<hsize_t>{5});
  CHECK(u.dims == std::vector<hsize_t>{5, 1});  // [output] dofs = ["b"]
  CHECK(lambda.dims == std::vector<hsize_t>{5, 1});
  CHECK(drift.dims == std::vector<hsize_t>{5, 2});
  for (std::size_t k = 0; k < rows.size(); ++k) {
    CAPTURE(k);
    CHECK(t.values[k] == rows[k][0]);
    CHECK(u.values[k] == rows[k][1]);
    CHECK(lambda.values[k] == rows[k][2]);
    CHECK(drift.values[2 * k] == rows[k][3]);
    CHECK(drift.values[2 * k + 1] == rows[k][4]);
  }
  CHECK(read_strings(file, "dof_names") == std::vector<std::string>{"b"});
  CHECK(read_strings(file, "constraint_names") == std::vector<std::string>{"tie"});
  CHECK(read_attribute(file, "rtol") == 1e-7);
  CHECK(read_attribute(file, "atol") == 1e-10);
  CHECK(H5Aexists(file, "scheme") > 0);
  CHECK(H5Lexists(file, "velocity", H5P_DEFAULT) == 0);  // not asked for
  H5Fclose(file);
}

TEST_CASE("a failed run with --out FILE.h5 keeps its rows in FILE.partial.h5") {
  const Sandbox box;
  box.write("p.toml", kPulledPendulumScene);
  const Result r = box.run("run p.toml --out out.h5");
  CHECK(r.code == 1);
  CHECK(r.err.find("out.partial.h5") != std::string::npos);
  const hid_t file = H5Fopen(box.path("out.partial.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  CHECK(read_doubles(file, "t").dims == std::vector<hsize_t>{10});  // t = 0 ... 0.9
  H5Fclose(file);
}

TEST_CASE("run --out FILE.h5 with acceleration: an nt x n dataset over the [output] dofs") {
  const Sandbox box;
  box.write("s.toml", replace(kTwoMassesScene, "output_step = 0.25\n",
                              "output_step = 0.25\n[output]\nquantities = "
                              "[\"displacement\", \"acceleration\"]\ndofs = [\"b\"]\n"));
  const Result h5 = box.run("run s.toml --out out.h5");
  CAPTURE(h5.err);
  REQUIRE(h5.code == 0);
  const Result csv = box.run("run s.toml --out out.csv");
  REQUIRE(csv.code == 0);
  const std::string text = slurp(box.path("out.csv"));
  CHECK(text.substr(0, text.find('\n')) == "t,b,acc_b");
  const auto rows = csv_rows(text);
  REQUIRE(rows.size() == 5);
  const hid_t file = H5Fopen(box.path("out.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const Dataset a = read_doubles(file, "acceleration");
  CHECK(a.dims == std::vector<hsize_t>{5, 1});
  for (std::size_t k = 0; k < rows.size(); ++k) {
    CAPTURE(k);
    CHECK(a.values[k] == rows[k][2]);
  }
  // At t = 0 the model is at rest, undisplaced and unloaded (the step starts at 0.25).
  CHECK(a.values[0] == 0.0);
  H5Fclose(file);
}

TEST_CASE("the energy balance: seven CSV columns, the same numbers in HDF5 with their names") {
  // Two masses, a load step at t = 0.25 and a support; rows from the CSV and the HDF5 file agree
  // bit for bit, and the balance closes (energy_error below 1e-7 J at rtol 1e-9; the load's work
  // is about 0.2 J by t = 1).
  const Sandbox box;
  box.write("s.toml", replace(kTwoMassesScene, "output_step = 0.25\n",
                              "output_step = 0.25\nrtol = 1e-9\natol = 1e-12\n[output]\n"
                              "quantities = [\"energy\"]\n"));
  const Result csv = box.run("run s.toml --out out.csv");
  CAPTURE(csv.err);
  REQUIRE(csv.code == 0);
  const std::string text = slurp(box.path("out.csv"));
  CHECK(text.substr(0, text.find('\n')) ==
        "t,energy,energy_error,energy_kinetic,energy_potential,energy_dissipated,work_loads,"
        "work_constraints");
  const auto rows = csv_rows(text);
  REQUIRE(rows.size() == 5);
  for (const auto& row : rows) {
    REQUIRE(row.size() == 8);
    CHECK(std::abs(row[2]) < 1e-7);
    CHECK(row[1] == doctest::Approx(row[3] + row[4]).epsilon(1e-15));
  }
  CHECK(rows.back()[6] > 0.05);  // work_loads at t = 1
  REQUIRE(box.run("run s.toml --out out.h5").code == 0);
  const hid_t file = H5Fopen(box.path("out.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const Dataset energy = read_doubles(file, "energy");
  CHECK(energy.dims == std::vector<hsize_t>{5, 7});
  for (std::size_t k = 0; k < rows.size(); ++k) {
    for (std::size_t c = 0; c < 7; ++c) CHECK(energy.values[7 * k + c] == rows[k][c + 1]);
  }
  CHECK(read_strings(file, "energy_columns") ==
        std::vector<std::string>{"energy", "energy_error", "energy_kinetic", "energy_potential",
                                 "energy_dissipated", "work_loads", "work_constraints"});
  H5Fclose(file);
}

}  // namespace test_cli_hdf5
