#include "python/compare_records.hpp"

#include "python/scene_from_python.hpp"

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
    d["message"] = system_text(r.message);
    d["reference"] = result.reference_kind;
    // A failed run has no figures (None), as runs.csv leaves them empty: 0 read as a perfect run.
    const auto figure = [&r](double v) {
      return r.ok ? number_or_none(v) : py::object(py::none());
    };
    const auto count = [&r](long v) {
      return r.ok ? py::object(py::int_(v)) : py::object(py::none());
    };
    d["error_u"] = figure(r.error_u);
    d["error_v"] = figure(r.error_v);
    d["error_reaction"] = figure(r.error_reaction);
    d["max_drift_position"] = figure(r.max_drift_position);
    d["max_drift_velocity"] = figure(r.max_drift_velocity);
    d["final_drift_position"] = figure(r.final_drift_position);
    d["final_drift_velocity"] = figure(r.final_drift_velocity);
    d["steps"] = count(r.steps);
    d["residual_evals"] = count(r.residual_evals);
    d["jacobian_evals"] = count(r.jacobian_evals);
    d["newton_failures"] = count(r.newton_failures);
    d["error_test_failures"] = count(r.error_test_failures);
    d["wall_median"] = figure(r.wall_median);
    d["wall_min"] = figure(r.wall_min);
    d["wall_max"] = figure(r.wall_max);
    d["repeats"] = count(r.repeats);
    d["mescd_u"] = number_or_none(r.mescd_u);
    d["mescd_v"] = number_or_none(r.mescd_v);
    d["energy_error"] = number_or_none(r.energy_error);
    // The mark of runs far beyond their target (CompareOptions::mark_factor).
    d["error_target"] = number_or_none(r.error_target);  // NaN: none (a fixed step)
    d["error_ratio"] = figure(r.error_ratio);
    d["over_tolerance"] = r.ok ? py::object(py::bool_(r.over_tolerance)) : py::object(py::none());
    out.append(d);
  }
  for (const auto& [scheme, reason] : result.skipped) {
    py::dict d;
    d["scheme"] = to_string(scheme);
    d["skipped"] = true;
    d["message"] = system_text(reason);
    // Every key of a run's record, None: a table of the records (d["rtol"]) needs no special case.
    for (const char* key : {"ok",
                            "reference",
                            "rtol",
                            "atol",
                            "error_u",
                            "error_v",
                            "error_reaction",
                            "max_drift_position",
                            "max_drift_velocity",
                            "final_drift_position",
                            "final_drift_velocity",
                            "steps",
                            "residual_evals",
                            "jacobian_evals",
                            "newton_failures",
                            "error_test_failures",
                            "wall_median",
                            "wall_min",
                            "wall_max",
                            "repeats",
                            "mescd_u",
                            "mescd_v",
                            "energy_error",
                            "error_target",
                            "error_ratio",
                            "over_tolerance"}) {
      d[key] = py::none();
    }
    out.append(d);
  }
  return out;
}

}  // namespace condyn::python
