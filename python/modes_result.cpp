#include "python/modes_result.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>

#include "python/scene_from_python.hpp"

namespace py = pybind11;

namespace condyn::python {

namespace {

py::array_t<double> vector_array(const Eigen::VectorXd& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

}  // namespace

py::dict modes_dict(const SceneModes& s) {
  const NaturalModes& m = s.modes;
  py::dict d;
  d["omega"] = vector_array(m.omega);
  d["frequency"] = vector_array(m.omega.unaryExpr(&mode_frequency));
  d["period"] = vector_array(m.omega.unaryExpr(&mode_period));
  if (s.ground_motion) {
    d["mass_ratio"] = vector_array(m.mass_ratio);
    d["mass_ratio_cumulative"] = vector_array(m.mass_ratio_cumulative);
    d["total_mass"] = m.total_mass;
  } else {
    d["mass_ratio"] = py::none();
    d["mass_ratio_cumulative"] = py::none();
    d["total_mass"] = py::none();
  }
  const auto n = static_cast<py::ssize_t>(m.shapes.rows());
  const auto k = static_cast<py::ssize_t>(m.shapes.cols());
  // Column-major n x k: strides of one double down a column, n across (copied).
  d["shapes"] = py::array_t<double>(
      {n, k},
      {static_cast<py::ssize_t>(sizeof(double)), static_cast<py::ssize_t>(sizeof(double)) * n},
      m.shapes.data());
  py::list names;
  for (const auto& name : s.dof_names) names.append(system_text(name));
  d["dof_names"] = names;
  d["available"] = m.available;
  d["solver"] = m.dense ? "dense" : "lanczos";
  return d;
}

}  // namespace condyn::python
