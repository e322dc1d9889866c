#pragma once
// condyn's HDF5 files read back through the C API, for the tests that compare them with the CSV
// (tests/src/test_cli_hdf5.cpp, test_cli_modes.cpp, test_output_map.cpp, test_cli_derived*.cpp).

#include <doctest/doctest.h>
#include <hdf5.h>

#include <string>
#include <vector>

#include "tests/csv_table.hpp"

namespace condyn::test {

/// A numeric dataset read as doubles: its dimensions and values (row-major).
struct Dataset {
  std::vector<hsize_t> dims;
  std::vector<double> values;
};

inline Dataset read_doubles(hid_t file, const char* name) {
  Dataset d;
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  REQUIRE(set >= 0);
  const hid_t space = H5Dget_space(set);
  d.dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, d.dims.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t n : d.dims) count *= n;
  d.values.resize(static_cast<std::size_t>(count));
  if (count > 0) {
    CHECK(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()) >= 0);
  }
  H5Sclose(space);
  H5Dclose(set);
  return d;
}

/// The class of a dataset's stored type (H5T_FLOAT, H5T_INTEGER, H5T_STRING).
inline H5T_class_t stored_class(hid_t file, const char* name) {
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  REQUIRE(set >= 0);
  const hid_t type = H5Dget_type(set);
  const H5T_class_t c = H5Tget_class(type);
  H5Tclose(type);
  H5Dclose(set);
  return c;
}

/// A dataset of variable-length UTF-8 strings (condyn's names).
inline std::vector<std::string> read_strings(hid_t file, const char* name) {
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  REQUIRE(set >= 0);
  const hid_t space = H5Dget_space(set);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  std::vector<char*> raw(static_cast<std::size_t>(n));
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);  // as written: names are UTF-8
  if (n > 0) CHECK(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) >= 0);
  std::vector<std::string> out(raw.begin(), raw.end());
  if (n > 0) H5Dvlen_reclaim(type, space, H5P_DEFAULT, raw.data());
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(set);
  return out;
}

/// A numeric root attribute, read as a double.
inline double read_attribute(hid_t file, const char* name) {
  double v = 0.0;
  const hid_t attr = H5Aopen(file, name, H5P_DEFAULT);
  REQUIRE(attr >= 0);
  CHECK(H5Aread(attr, H5T_NATIVE_DOUBLE, &v) >= 0);
  H5Aclose(attr);
  return v;
}

/// A variable-length UTF-8 string root attribute (the scheme, the modes' solver).
inline std::string read_string_attribute(hid_t file, const char* name) {
  const hid_t attr = H5Aopen(file, name, H5P_DEFAULT);
  REQUIRE(attr >= 0);
  const hid_t type = H5Aget_type(attr);
  char* text = nullptr;
  CHECK(H5Aread(attr, type, static_cast<void*>(&text)) >= 0);
  std::string out = text == nullptr ? "" : text;
  H5free_memory(text);
  H5Tclose(type);
  H5Aclose(attr);
  return out;
}

/// The result file `path`'s `derived` dataset holds the columns `names`, in that order, each value
/// exactly the CSV's (written from the same doubles).
inline void check_derived_as_csv(const std::string& path, const CsvTable& csv,
                                 const std::vector<std::string>& names) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  CHECK(read_strings(file, "derived_names") == names);
  const Dataset d = read_doubles(file, "derived");
  H5Fclose(file);
  const std::size_t rows = csv.columns.at("t").size();
  REQUIRE(d.dims == std::vector<hsize_t>{rows, names.size()});
  std::size_t differ = 0;
  for (std::size_t k = 0; k < rows; ++k) {
    for (std::size_t j = 0; j < names.size(); ++j)
      differ += d.values[k * names.size() + j] == csv.columns.at(names[j])[k] ? 0 : 1;
  }
  CHECK(differ == 0);
}

}  // namespace condyn::test
