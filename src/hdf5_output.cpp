#include "src/hdf5_output.hpp"

#include <hdf5.h>

#include <stdexcept>
#include <vector>

namespace condyn {

namespace {

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

void check(herr_t status, const char* call) {
  if (status < 0) throw std::runtime_error(std::string("HDF5: ") + call + " failed");
}

/// A rows x cols dataset of doubles, row-major (HDF5's order), entry (r, c) = get(r, c); cols = 0
/// makes a vector of `rows` entries get(r, 0).
template <class Get>
void put_matrix(hid_t file, const char* name, hsize_t rows, hsize_t cols, const Get& get) {
  const hsize_t width = cols == 0 ? 1 : cols;
  std::vector<double> data(static_cast<std::size_t>(rows * width));
  for (hsize_t r = 0; r < rows; ++r) {
    for (hsize_t c = 0; c < width; ++c) data[static_cast<std::size_t>(r * width + c)] = get(r, c);
  }
  const hsize_t dims[2] = {rows, cols};
  const Handle space(H5Screate_simple(cols == 0 ? 1 : 2, dims, nullptr), H5Sclose,
                     "H5Screate_simple");
  const Handle set(
      H5Dcreate2(file, name, H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose, "H5Dcreate2");
  if (!data.empty()) {
    check(H5Dwrite(set.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          "H5Dwrite");
  }
}

void put_strings(hid_t file, const char* name, const std::vector<std::string>& values) {
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

void put_attribute(hid_t file, const char* name, double value) {
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate");
  const Handle attr(H5Acreate2(file, name, H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                    H5Aclose, "H5Acreate2");
  check(H5Awrite(attr.id(), H5T_NATIVE_DOUBLE, &value), "H5Awrite");
}

void put_attribute(hid_t file, const char* name, const std::string& value) {
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy");
  check(H5Tset_size(type.id(), value.empty() ? 1 : value.size()), "H5Tset_size");
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate");
  const Handle attr(H5Acreate2(file, name, type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
                    H5Aclose, "H5Acreate2");
  check(H5Awrite(attr.id(), type.id(), value.c_str()), "H5Awrite");
}

}  // namespace

bool is_hdf5_path(const std::string& path) {
  return path.size() >= 3 && path.compare(path.size() - 3, 3, ".h5") == 0;
}

void write_hdf5(std::ostream& out, const Model& model, const OutputSpec& output,
                const RunAttributes& run, const Trajectory& traj) {
  // The file lives in memory (the core driver, no backing store); its image is then written to
  // `out`, so the caller's checked temporary file and atomic rename apply to it as to a CSV.
  const Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate");
  check(H5Pset_fapl_core(access.id(), 1 << 20, 0), "H5Pset_fapl_core");
  const Handle file(H5Fcreate("condyn-output.h5", H5F_ACC_TRUNC, H5P_DEFAULT, access.id()),
                    H5Fclose, "H5Fcreate");
  const hid_t f = file.id();
  const auto nt = static_cast<hsize_t>(traj.t.size());
  const std::vector<int> shown = selected_dofs(output, model.dof_names);
  std::vector<std::string> dof_names, constraint_names;
  for (int d : shown) dof_names.push_back(model.dof_names[static_cast<std::size_t>(d)]);
  for (const auto& c : model.constraints) constraint_names.push_back(c.name);
  put_matrix(f, "t", nt, 0, [&](hsize_t r, hsize_t) { return traj.t[r]; });
  const auto dofs = [&](const char* name, const Eigen::MatrixXd& m) {
    put_matrix(f, name, nt, shown.size(),
               [&](hsize_t r, hsize_t c) { return m(shown[c], static_cast<Eigen::Index>(r)); });
  };
  for (Quantity q : output.quantities) {
    switch (q) {
      case Quantity::displacement:
        dofs("displacement", traj.u);
        break;
      case Quantity::velocity:
        dofs("velocity", traj.v);
        break;
      case Quantity::reaction:
        dofs("reaction", traj.reaction);
        break;
      case Quantity::multiplier:
        put_matrix(f, "multiplier", nt, static_cast<hsize_t>(traj.multiplier.rows()),
                   [&](hsize_t r, hsize_t c) {
                     return traj.multiplier(static_cast<Eigen::Index>(c),
                                            static_cast<Eigen::Index>(r));
                   });
        break;
      case Quantity::drift:
        put_matrix(f, "drift", nt, 2, [&](hsize_t r, hsize_t c) {
          const auto k = static_cast<Eigen::Index>(r);
          return c == 0 ? traj.drift_position[k] : traj.drift_velocity[k];
        });
        break;
      case Quantity::energy:  // build_model refuses 'energy' for nonconservative scenes
        put_matrix(f, "energy", nt, 2, [&](hsize_t r, hsize_t c) {
          const auto k = static_cast<Eigen::Index>(r);
          return c == 0 ? traj.energy[k] : traj.energy[k] - traj.energy[0];
        });
        break;
    }
  }
  put_strings(f, "dof_names", dof_names);
  put_strings(f, "constraint_names", constraint_names);
  put_attribute(f, "scheme", run.scheme);
  put_attribute(f, "rtol", run.rtol);
  put_attribute(f, "atol", run.atol);
  check(H5Fflush(f, H5F_SCOPE_GLOBAL), "H5Fflush");
  const ssize_t size = H5Fget_file_image(f, nullptr, 0);
  if (size < 0) throw std::runtime_error("HDF5: H5Fget_file_image failed");
  std::vector<char> image(static_cast<std::size_t>(size));
  if (H5Fget_file_image(f, image.data(), image.size()) != size) {
    throw std::runtime_error("HDF5: H5Fget_file_image failed");
  }
  out.write(image.data(), static_cast<std::streamsize>(image.size()));
}

}  // namespace condyn
