#include "python/compare_records.hpp"

#include <cmath>

namespace py = pybind11;

namespace condyn::python {

namespace {

py::object number_or_none(double x) {
  return std::isnan(x) ? py::object(py::none()) : py::object(py::float_(x));
}

}  // namespace

py::list compare_records(const CompareResult& result) {
  py::list out;
  for (const RunRecord& r : result.runs) {
    py::dict d;
    d["scheme"] = to_string(r.scheme);
    d["rtol"] = r.rtol;
    d["atol"] = r.atol;
    d["ok"] = r.ok;
    d["skipped"] = false;
    d["message"] = r.message;
    d["reference"] = result.reference_kind;
    d["error_u"] = r.error_u;
    d["error_v"] = r.error_v;
    d["error_reaction"] = r.error_reaction;
    d["max_drift_position"] = r.max_drift_position;
    d["max_drift_velocity"] = r.max_drift_velocity;
    d["final_drift_position"] = r.final_drift_position;
    d["final_drift_velocity"] = r.final_drift_velocity;
    d["steps"] = r.steps;
    d["residual_evals"] = r.residual_evals;
    d["jacobian_evals"] = r.jacobian_evals;
    d["newton_failures"] = r.newton_failures;
    d["error_test_failures"] = r.error_test_failures;
    d["wall_median"] = r.wall_median;
    d["wall_min"] = r.wall_min;
    d["wall_max"] = r.wall_max;
    d["repeats"] = r.repeats;
    d["mescd_u"] = number_or_none(r.mescd_u);
    d["mescd_v"] = number_or_none(r.mescd_v);
    d["energy_error"] = number_or_none(r.energy_error);
    out.append(d);
  }
  for (const auto& [scheme, reason] : result.skipped) {
    py::dict d;
    d["scheme"] = to_string(scheme);
    d["ok"] = false;
    d["skipped"] = true;
    d["message"] = reason;
    d["reference"] = result.reference_kind;
    out.append(d);
  }
  return out;
}

}  // namespace condyn::python
