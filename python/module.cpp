// The extension module condyn._condyn (python/condyn/__init__.py re-exports it): run and compare
// over the same libraries as the CLI. Scenes are parsed with the GIL held (they are Python
// objects); building the model and integrating release it, so threads run scenes side by side,
// and Ctrl-C stops a run (KeyboardInterrupt) within a tenth of a second.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dae/interface/interrupt.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "models/scene/toml_access.hpp"
#include "python/compare_records.hpp"
#include "python/modes_result.hpp"
#include "python/run_result.hpp"
#include "python/scene_from_python.hpp"
#include "src/output/csv_output.hpp"
#include "src/output/temp_registry.hpp"
#include "validation/studies/compare.hpp"
#include "validation/studies/scene_modes.hpp"
#include "validation/studies/user_checks.hpp"

namespace py = pybind11;
using namespace condyn;

namespace {

/// Runs `body` without the GIL, so threads run scenes side by side. Ctrl-C stops it: the step
/// driver polls Python's signal handlers (dae/interface/interrupt.hpp), and the exception the
/// handler set (KeyboardInterrupt) is raised here, once the GIL is back.
template <class Body>
void without_gil(const Body& body) {
  try {
    const py::gil_scoped_release free;
    body();
  } catch (const Interrupted&) {
    throw py::error_already_set();
  }
}

/// An argument of run()/compare() out of range: a SceneError naming the scene and the argument.
[[noreturn]] void bad_argument(const SceneSpec& spec, const std::string& argument,
                               const std::string& problem) {
  throw SceneError(scene_message(spec.file, SourcePoint{argument, 0}, problem));
}

Scheme scheme_argument(const SceneSpec& spec, const std::string& argument, const std::string& s) {
  const auto scheme = scheme_from_string(s);
  if (!scheme) bad_argument(spec, argument, "unknown scheme '" + s + "': " + scheme_names());
  return *scheme;
}

/// The scene with run()'s overrides (`step`: the Newmark family's fixed step, as --step), checked
/// as the parser checks [solve]; `set_aside` gets the note of SolveSpec::override_scheme.
SceneSpec run_spec(const py::handle& scene, const std::optional<std::string>& scheme,
                   std::optional<double> rtol, std::optional<double> atol,
                   std::optional<double> step, std::string& set_aside) {
  SceneSpec spec = python::parse_python_scene(scene);
  if (scheme) set_aside = spec.solve.override_scheme(scheme_argument(spec, "scheme", *scheme));
  if (rtol) {
    if (!(std::isfinite(*rtol) && *rtol >= kMinRtol && *rtol < 1.0)) {
      bad_argument(spec, "rtol", "must lie in [1e-15, 1) (got " + TomlAccess::fmt(*rtol) + ")");
    }
    spec.solve.rtol = *rtol;
  }
  if (atol) {
    if (!(std::isfinite(*atol) && *atol >= kMinAtol)) {
      bad_argument(spec, "atol",
                   "must be a finite number >= 1e-100 (got " + TomlAccess::fmt(*atol) + ")");
    }
    spec.solve.atol = *atol;
  }
  if (step) spec.solve.step = *step;  // validate() refuses a step out of (0, t_end]
  try {
    spec.solve.validate();
  } catch (const std::invalid_argument& e) {
    bad_argument(spec, "", e.what());
  }
  return spec;
}

/// The failure kind as an identifier, the enum's own name (a sweep's status column, docs/sweep.md;
/// to_string gives the words messages use).
const char* failure_kind_name(FailureKind kind) {
  switch (kind) {
    case FailureKind::unknown:
      return "unknown";
    case FailureKind::non_finite:
      return "non_finite";
    case FailureKind::residual_non_finite:
      return "residual_non_finite";
    case FailureKind::step_budget:
      return "step_budget";
    case FailureKind::wall_time_budget:
      return "wall_time_budget";
    case FailureKind::steps_per_output:
      return "steps_per_output";
    case FailureKind::step_size_collapsed:
      return "step_size_collapsed";
    case FailureKind::convergence:
      return "convergence";
    case FailureKind::error_test:
      return "error_test";
    case FailureKind::tolerance_too_tight:
      return "tolerance_too_tight";
    case FailureKind::linear_solver:
      return "linear_solver";
    case FailureKind::first_step:
      return "first_step";
    case FailureKind::bad_input:
      return "bad_input";
    case FailureKind::interrupted:
      return "interrupted";
  }
  return "unknown";
}

/// condyn.check's dict of a verdict (docs/python.md); `checks` lists each check of `specs`.
py::dict check_dict(SceneCheckResult result, const std::vector<CheckSpec>& specs);

/// (result dict, failure message or None, failure kind or None, check dict or None): the Python
/// side raises IntegrationError with the partial result and the kind. With `checks`, the scene's
/// [[check]] tables are evaluated on this run's rows (the quantities they read computed too), as
/// condyn.check would evaluate them on a run of its own. With `out` (a file name, not blank), the
/// result is written there as `condyn run --out` writes it, a failed run's rows to the partial
/// file, the failure message saying where they went.
py::tuple run(const py::handle& scene, const std::optional<std::string>& scheme,
              std::optional<double> rtol, std::optional<double> atol, std::optional<double> step,
              bool checks, const std::optional<std::string>& out) {
  std::string set_aside;
  SceneSpec spec = run_spec(scene, scheme, rtol, atol, step, set_aside);
  // The output is checked before any work, as the command checks it, with the scene's own
  // [output] (before the checks add the quantities they read). A dict scene is no input file.
  std::optional<RunOutputs> outputs;
  if (out) {
    outputs.emplace(py::isinstance<py::dict>(scene) ? std::string() : spec.file, *out, spec.output,
                    "", spec.input_files, "out");
  }
  checks = checks && !spec.checks.empty();
  if (checks) add_check_quantities(spec);
  const std::vector<CheckSpec> specs = spec.checks;
  BuildReport report;
  std::optional<Model> model;
  std::optional<CheckEvaluator> evaluator;
  SolveResult result;
  without_gil([&] {
    try {
      model.emplace(build_model(spec, report));
      if (!set_aside.empty()) report.warnings.insert(report.warnings.begin(), set_aside);
      // A bad [[check]] is bad input here as in the command's run (which refuses it, exit 2).
      if (!spec.checks.empty()) evaluator.emplace(*model, spec.checks, spec.file);
      release_model_input(spec);
      std::vector<Quantity> quantities =
          with_derived_quantities(spec.output.quantities, model->derived);
      if (checks) quantities = with_check_quantities(std::move(quantities), *evaluator);
      RunHooks hooks = hooks_for(quantities);
      hooks.reactions = true;  // the result holds every row's reaction and multipliers
      result = solve(*model, spec.solve, hooks);
      if (checks && result.ok()) {
        for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(result.trajectory.t.size()); ++k)
          evaluator->add(row_of(result.trajectory, k));
      }
    } catch (const SchemeNotApplicable& e) {
      // Bad input, as in the CLI (exit 2): the scene and the scheme do not go together.
      throw SceneError(scene_message(spec.file, e.where(), e.what()));
    }
  });
  const py::object verdict =
      checks
          ? py::object(check_dict(
                check_verdict(spec.file, spec.solve, result, *evaluator, report.warnings), specs))
          : py::object(py::none());
  // Written with the GIL held: the HDF5 library and the temporary files' registry serve one
  // thread at a time. The whole result is in hand (nothing was streamed), as the Result needs it.
  const std::string partial =
      outputs ? outputs->keep(*model, run_attributes(*model, spec.solve, result.scheme),
                              result.trajectory, result.ok())
              : std::string();
  const py::object failure =
      result.ok() ? py::object(py::none())
                  : python::system_text(failure_message(result, spec.solve.t_end, partial));
  const py::object kind = result.ok()
                              ? py::object(py::none())
                              : py::object(py::str(failure_kind_name(result.failure->kind)));
  return py::make_tuple(
      python::result_dict(std::move(result), *model, spec.solve, report, spec.output), failure,
      kind, verdict);
}

py::tuple compare(const py::handle& scene, const std::optional<std::vector<double>>& tolerances,
                  const std::optional<std::vector<std::string>>& schemes,
                  const std::optional<int>& repeats, const std::optional<double>& drift_rtol,
                  long max_steps, double max_wall_time, std::optional<double> step) {
  SceneSpec spec = python::parse_python_scene(scene);
  if (step) {  // the Newmark family's fixed step, as compare --step
    spec.solve.step = *step;
    try {
      spec.solve.validate();
    } catch (const std::invalid_argument& e) {
      bad_argument(spec, "", e.what());
    }
  }
  CompareOptions options;
  options.repeats = 1;  // the CLI repeats runs for stable wall times; a script asks for more
  if (tolerances) options.tolerances = *tolerances;
  if (schemes) {
    options.schemes.clear();
    for (const auto& s : *schemes) {
      const Scheme scheme = scheme_argument(spec, "schemes", s);
      if (scheme == Scheme::automatic) bad_argument(spec, "schemes", "name schemes, not 'auto'");
      options.schemes.push_back(scheme);
    }
  }
  if (repeats) options.repeats = *repeats;
  if (drift_rtol) options.drift_rtol = *drift_rtol;
  options.max_steps = max_steps;
  options.max_wall_time = max_wall_time;
  try {
    options.validate();
  } catch (const std::invalid_argument& e) {
    bad_argument(spec, "", e.what());
  }
  CompareResult result;
  std::string no_reference;
  without_gil([&] {
    try {
      result = run_compare(spec, options);
    } catch (const SchemeNotApplicable& e) {
      throw SceneError(scene_message(spec.file, e.where(), e.what()));
    } catch (const NoReferenceError& e) {
      no_reference = e.what();  // raised as IntegrationError, as a run's failure
    }
  });
  if (!no_reference.empty()) {
    return py::make_tuple(py::list(), py::list(), python::system_text(no_reference));
  }
  py::list warnings;
  for (const auto& w : result.warnings) warnings.append(python::system_text(w));
  return py::make_tuple(python::compare_records(result), warnings, py::none());
}

/// The scene's [[check]] tables, evaluated on one run: (scene, scheme, steps, wall_s, failure,
/// one dict per check).
py::dict check(const py::handle& scene, const std::optional<std::string>& scheme,
               std::optional<double> step) {
  SceneSpec spec = python::parse_python_scene(scene, SceneNeeds{.checks = true});
  SceneCheckOptions options;
  if (scheme) options.scheme = scheme_argument(spec, "scheme", *scheme);
  options.step = step;
  const std::string file = spec.file;
  const std::vector<CheckSpec> specs = spec.checks;  // a failed run's checks are still listed
  SceneCheckResult result;
  without_gil([&] {
    try {
      result = run_scene_checks(std::move(spec), options);
    } catch (const SchemeNotApplicable& e) {
      throw SceneError(scene_message(file, e.where(), e.what()));
    }
  });
  return check_dict(std::move(result), specs);
}

py::dict check_dict(SceneCheckResult result, const std::vector<CheckSpec>& specs) {
  // A failed run evaluates no check: each still gets its dict, NaN and not passed (docs/python.md).
  if (!result.failure.empty()) result.outcomes = unevaluated_outcomes(specs);
  py::list checks;
  for (const CheckOutcome& o : result.outcomes) {
    py::dict d;
    d["quantity"] = python::system_text(o.quantity);
    d["computed"] = o.computed;
    d["bound"] = o.bound;
    d["passed"] = o.passed;
    d["text"] = python::system_text(o.text);
    checks.append(d);
  }
  py::dict d;
  d["scene"] = python::system_text(result.scene);
  d["scheme"] = result.scheme;
  d["steps"] = result.steps;
  d["wall_s"] = result.wall_s;
  d["failure"] =
      result.failure.empty() ? py::object(py::none()) : python::system_text(result.failure);
  d["checks"] = checks;
  // A drift beyond the tolerance fails the scene whatever its checks say (docs/checks.md).
  d["drift"] = result.drift.empty() ? py::object(py::none()) : python::system_text(result.drift);
  py::list warnings;
  for (const auto& w : result.warnings) warnings.append(python::system_text(w));
  d["warnings"] = warnings;
  d["passed"] = result.passed();
  return d;
}

/// The scene's natural modes, as `condyn modes` gives them (python/modes_result.hpp).
py::dict modes(const py::handle& scene, std::optional<int> count) {
  const SceneSpec spec = python::parse_python_scene(scene);
  SceneModes result;
  without_gil([&] {
    try {
      result = scene_modes(spec, count, "count");
    } catch (const SchemeNotApplicable& e) {
      throw SceneError(scene_message(spec.file, e.where(), e.what()));
    }
  });
  return python::modes_dict(result);
}

}  // namespace

PYBIND11_MODULE(_condyn, m) {
  m.doc() = "condyn: constrained dynamic systems (C++ core; use the condyn package)";
  // Messages quote file names as the system gave them: bytes that are not UTF-8 come back as
  // Python's surrogateescape, the str that names the same file.
  static py::exception<SceneError> scene_error(m, "SceneError", PyExc_ValueError);
  // run(..., out=...): a name condyn run --out would refuse, refused before any work.
  static py::exception<OutputError> output_error(m, "OutputError", PyExc_ValueError);
  // By value: pybind11 takes a plain function pointer void (*)(std::exception_ptr).
  py::register_exception_translator(
      [](std::exception_ptr p) {  // NOLINT(performance-unnecessary-value-param)
        try {
          if (p) std::rethrow_exception(p);
        } catch (const SceneError& e) {
          PyErr_SetObject(scene_error.ptr(), python::system_text(e.what()).ptr());
        } catch (const OutputError& e) {
          PyErr_SetObject(output_error.ptr(), python::system_text(e.what()).ptr());
        }
      });
  // Python keeps its own signal handlers (Ctrl-C: KeyboardInterrupt): an output's temporary file
  // is removed by its owner on every return and exception instead (src/output/temp_registry.hpp).
  use_signal_handlers(false);
  // Ctrl-C during a run: Python's handler runs (with the GIL, from the running thread; only the
  // main thread's handlers run) and its exception, KeyboardInterrupt, stays set for without_gil.
  set_interrupt_poll([] {
    const py::gil_scoped_acquire gil;
    return PyErr_CheckSignals() != 0;
  });
  m.def("run", &run, py::arg("scene"), py::arg("scheme") = py::none(), py::arg("rtol") = py::none(),
        py::arg("atol") = py::none(), py::arg("step") = py::none(), py::arg("checks") = false,
        py::arg("out") = py::none());
  m.def("compare", &compare, py::arg("scene"), py::arg("tolerances") = py::none(),
        py::arg("schemes") = py::none(), py::arg("repeats") = py::none(),
        py::arg("drift_rtol") = py::none(), py::arg("max_steps") = 0,
        py::arg("max_wall_time") = 0.0, py::arg("step") = py::none());
  m.def("check", &check, py::arg("scene"), py::arg("scheme") = py::none(),
        py::arg("step") = py::none());
  m.def("modes", &modes, py::arg("scene"), py::arg("count") = py::none());
  m.def("scheme_names", &scheme_names);
  // Parses a scene (a path or a dict) and builds nothing: a sweep checks its scenes before it
  // runs any (docs/sweep.md). Raises SceneError as run() does.
  m.def("parse_scene", [](const py::handle& scene) { (void)python::parse_python_scene(scene); });
}
