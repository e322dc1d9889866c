#pragma once
// The HDF5 pieces every writer uses (src/output/hdf5_output.cpp a whole result,
// src/output/row_writer.cpp row by row, src/output/hdf5_modes.cpp the modes): handles closed on
// scope exit, checked calls, the in-memory file, numeric and string datasets, root attributes.

#include <hdf5.h>

#include <cstdint>
#include <ostream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "src/output/hdf5_output.hpp"
#include "src/output/output_columns.hpp"

namespace condyn::hdf5 {

/// Closes an HDF5 handle with its own close function when it leaves scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const char* call) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error(std::string("HDF5: ") + call + " failed");
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { close_(id_); }
  [[nodiscard]] hid_t id() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

inline void check(herr_t status, const char* call) {
  if (status < 0) throw std::runtime_error(std::string("HDF5: ") + call + " failed");
}

/// An HDF5 file built in memory (the core driver, no backing store) and then written to a stream
/// as one image, so that the caller's checked temporary file and atomic rename apply to it as to
/// a CSV.
class MemoryFile {
 public:
  MemoryFile()
      : access_(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate"),
        file_(create(access_.id()), H5Fclose, "H5Fcreate") {}
  [[nodiscard]] hid_t id() const { return file_.id(); }

  /// Flushes the file and writes its image to `out`.
  void write_to(std::ostream& out) const {
    check(H5Fflush(file_.id(), H5F_SCOPE_GLOBAL), "H5Fflush");
    const ssize_t size = H5Fget_file_image(file_.id(), nullptr, 0);
    if (size < 0) throw std::runtime_error("HDF5: H5Fget_file_image failed");
    std::vector<char> image(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file_.id(), image.data(), image.size()) != size) {
      throw std::runtime_error("HDF5: H5Fget_file_image failed");
    }
    out.write(image.data(), static_cast<std::streamsize>(image.size()));
  }

 private:
  static hid_t create(hid_t access) {
    check(H5Pset_fapl_core(access, 1 << 20, 0), "H5Pset_fapl_core");
    return H5Fcreate("condyn-output.h5", H5F_ACC_TRUNC, H5P_DEFAULT, access);
  }
  Handle access_;
  Handle file_;
};

/// A rows x cols dataset, row-major (HDF5's order), entry (r, c) = get(r, c); cols = 0 makes a
/// vector of `rows` entries get(r, 0). Doubles (get returns double) are stored as 64-bit IEEE,
/// whole numbers (get returns std::int64_t: mode numbers) as 64-bit integers.
template <class Get>
void put_matrix(hid_t file, const char* name, hsize_t rows, hsize_t cols, const Get& get) {
  using Value = std::invoke_result_t<const Get&, hsize_t, hsize_t>;
  static_assert(std::is_same_v<Value, double> || std::is_same_v<Value, std::int64_t>);
  constexpr bool whole = std::is_same_v<Value, std::int64_t>;
  const hsize_t width = cols == 0 ? 1 : cols;
  std::vector<Value> data(static_cast<std::size_t>(rows * width));
  for (hsize_t r = 0; r < rows; ++r) {
    for (hsize_t c = 0; c < width; ++c) data[static_cast<std::size_t>(r * width + c)] = get(r, c);
  }
  const hsize_t dims[2] = {rows, cols};
  const Handle space(H5Screate_simple(cols == 0 ? 1 : 2, dims, nullptr), H5Sclose,
                     "H5Screate_simple");
  const Handle set(H5Dcreate2(file, name, whole ? H5T_STD_I64LE : H5T_IEEE_F64LE, space.id(),
                              H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   H5Dclose, "H5Dcreate2");
  if (!data.empty()) {
    check(H5Dwrite(set.id(), whole ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                   H5P_DEFAULT, data.data()),
          "H5Dwrite");
  }
}

inline void put_strings(hid_t file, const char* name, const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const auto& v : values) pointers.push_back(v.c_str());
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy");
  check(H5Tset_size(type.id(), H5T_VARIABLE), "H5Tset_size");
  check(H5Tset_cset(type.id(), H5T_CSET_UTF8), "H5Tset_cset");
  const hsize_t dims[1] = {values.size()};
  const Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose, "H5Screate_simple");
  const Handle set(
      H5Dcreate2(file, name, type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose, "H5Dcreate2");
  if (!values.empty()) {
    check(H5Dwrite(set.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()),
          "H5Dwrite");
  }
}

inline void put_attribute(hid_t file, const char* name, double value) {
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate");
  const Handle attr(H5Acreate2(file, name, H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                    H5Aclose, "H5Acreate2");
  check(H5Awrite(attr.id(), H5T_NATIVE_DOUBLE, &value), "H5Awrite");
}

/// A whole number (a count), as a 64-bit integer.
inline void put_attribute(hid_t file, const char* name, std::int64_t value) {
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate");
  const Handle attr(H5Acreate2(file, name, H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                    H5Aclose, "H5Acreate2");
  check(H5Awrite(attr.id(), H5T_NATIVE_INT64, &value), "H5Awrite");
}

/// A variable-length UTF-8 string, as the name datasets: h5py reads it as str (a fixed-length
/// ASCII one came back as bytes, b'ggl', unequal to 'ggl').
inline void put_attribute(hid_t file, const char* name, const std::string& value) {
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy");
  check(H5Tset_size(type.id(), H5T_VARIABLE), "H5Tset_size");
  check(H5Tset_cset(type.id(), H5T_CSET_UTF8), "H5Tset_cset");
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate");
  const Handle attr(H5Acreate2(file, name, type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
                    H5Aclose, "H5Acreate2");
  const char* text = value.c_str();
  check(H5Awrite(attr.id(), type.id(), static_cast<const void*>(&text)), "H5Awrite");
}

/// The column names of a result file: `dof_names` (the displacement columns shown) and
/// `constraint_names`; for a mapped model also `velocity_names`, `acceleration_names`,
/// `reaction_names` (each quantity's columns shown) and, with [output] points, `point_names`
/// (the `points` dataset's columns, `crank.B.x`).
inline void put_column_names(hid_t file, const OutputColumns& columns) {
  put_strings(file, "dof_names", columns.shown_names(Quantity::displacement));
  std::vector<std::string> constraint_names;
  for (const auto& c : columns.model().constraints) constraint_names.push_back(c.name);
  put_strings(file, "constraint_names", constraint_names);
  if (!columns.mapped()) return;
  put_strings(file, "velocity_names", columns.shown_names(Quantity::velocity));
  put_strings(file, "acceleration_names", columns.shown_names(Quantity::acceleration));
  put_strings(file, "reaction_names", columns.shown_names(Quantity::reaction));
  if (!columns.points().empty()) put_strings(file, "point_names", columns.point_columns());
}

/// The root attributes of a result file: scheme, rtol, atol, and constraints when it is set.
inline void put_run_attributes(hid_t file, const RunAttributes& run) {
  put_attribute(file, "scheme", run.scheme);
  put_attribute(file, "rtol", run.rtol);
  put_attribute(file, "atol", run.atol);
  if (!run.constraints.empty()) put_attribute(file, "constraints", run.constraints);
}

}  // namespace condyn::hdf5
