// The modes file's writer (src/output/hdf5_modes.hpp) on modes given by hand: each dataset and
// attribute holds what it was given (the table's columns through mode_frequency and mode_period,
// as the CSV's), the layout the Lanczos path and a rigid motion get, and names in UTF-8.
#include <doctest/doctest.h>
#include <hdf5.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "src/output/hdf5_modes.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/hdf5_read.hpp"

using namespace condyn;

namespace test_hdf5_modes {

using condyn::test::read_doubles;

TEST_CASE("the modes HDF5 file holds the modes it is given, a rigid motion's infinite period too") {
  SceneModes s;
  s.dof_names = {"u1", "ü2", "u3"};
  s.modes.omega = Eigen::Vector2d(0.0, 3.5);
  s.modes.shapes.resize(3, 2);
  s.modes.shapes << 0.25, -0.5, 0.5, 1.0 / 3.0, 0.75, 0.125;
  s.modes.available = 3;
  s.modes.dense = false;  // the Lanczos path's name
  const test::Sandbox box;
  {
    std::ofstream out(box.path("m.h5"), std::ios::binary);
    write_modes_hdf5(out, s);
  }
  const hid_t file = H5Fopen(box.path("m.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  CHECK(test::stored_class(file, "mode") == H5T_INTEGER);
  CHECK(read_doubles(file, "mode").values == std::vector<double>{1.0, 2.0});
  CHECK(read_doubles(file, "omega").values == std::vector<double>{0.0, 3.5});
  CHECK(read_doubles(file, "frequency").values == std::vector<double>{0.0, mode_frequency(3.5)});
  const auto period = read_doubles(file, "period").values;
  REQUIRE(period.size() == 2);
  CHECK(std::isinf(period[0]));
  CHECK(period[1] == mode_period(3.5));
  // Row-major n x K: row i the DOF dof_names[i].
  const test::Dataset phi = read_doubles(file, "shapes");
  CHECK(phi.dims == std::vector<hsize_t>{3, 2});
  CHECK(phi.values == std::vector<double>{0.25, -0.5, 0.5, 1.0 / 3.0, 0.75, 0.125});
  CHECK(test::read_strings(file, "dof_names") == s.dof_names);
  CHECK(test::read_string_attribute(file, "solver") == "lanczos");
  CHECK(test::read_attribute(file, "available") == 3.0);
  // No [ground_motion]: neither the ratios nor the total mass.
  CHECK(H5Lexists(file, "mass_ratio", H5P_DEFAULT) == 0);
  CHECK(H5Aexists(file, "total_mass") == 0);
  H5Fclose(file);
}

}  // namespace test_hdf5_modes
