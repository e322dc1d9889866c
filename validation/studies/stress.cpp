// The stress suite's runner: a reference per case, then every case under its schemes on a few
// threads, each run judged holds, inaccurate, failed or refused. The cases: stress_families.cpp.
#include "validation/studies/stress.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <iomanip>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/references/exact_solution.hpp"

namespace condyn {

namespace {

/// The reference of one case: the exact solution where it exists, else GGL at rtol 1e-11.
struct Reference {
  std::optional<Trajectory> trajectory;
  std::string kind = "none";
};

Reference make_reference(const SceneSpec& spec) {
  Reference r;
  try {
    const Model model = build_model(spec);
    try {
      r.trajectory = exact_trajectory(model, spec.solve.output_times());
      r.kind = "exact";
      return r;
    } catch (const ExactSolutionUnavailable&) {
      // fall through to a tight GGL run
    }
    SolveSpec tight = spec.solve;
    tight.scheme = Scheme::ggl;
    tight.rtol = 1e-11;
    tight.atol = 1e-13;
    tight.max_steps = 2000000;
    // Between two outputs the default budget, not max_steps: a reference that cannot be had
    // (the dead point at eps 1e-4) gives up after 10⁵ steps, as it did under the hidden cap.
    tight.max_steps_per_output = kDefaultStepsPerOutput;
    const SolveResult run = solve(model, tight);
    r.trajectory = succeeded(run).trajectory;
    r.kind = "ggl at rtol 1e-11";
  } catch (const std::exception&) {
    // No reference: the scene is refused, or even tight GGL fails (the records say why).
    r.trajectory.reset();
    r.kind = "none";
  }
  return r;
}

StressRecord run_one(const StressCase& c, const SceneSpec& spec, const Reference& ref,
                     Scheme scheme) {
  StressRecord r;
  r.family = c.family;
  r.label = c.label;
  r.parameter = c.parameter;
  r.case_id = c.id;
  r.scheme = scheme;
  r.rtol = spec.solve.rtol;
  r.drift_limit = c.drift_limit;
  r.reference = ref.kind;
  const auto start = std::chrono::steady_clock::now();
  try {
    const Model model = build_model(spec);
    if (auto why = scheme_refusal(model, scheme)) {
      r.status = "refused";
      r.reason = *why;
      return r;
    }
    SolveSpec settings = spec.solve;
    settings.scheme = scheme;
    settings.max_steps = c.max_steps;
    settings.max_steps_per_output = kDefaultStepsPerOutput;  // as for the reference
    const SolveResult result = solve(model, settings);
    const SolveSummary& summary = result.summary;
    if (const auto& failure = result.failure) {
      r.status = "failed";
      r.reason = failure->message;
      r.suggestion = failure->suggestion;
      r.t_reached = failure->t_reached;
    } else {
      const Trajectory& run = result.trajectory;
      r.steps = summary.steps;
      r.max_drift_position = summary.max_drift_position;
      r.max_drift_velocity = summary.max_drift_velocity;
      r.t_reached = run.t.back();
      if (const double e = relative_energy_error(run); e >= 0.0) r.energy_error = e;
      if (ref.trajectory) r.error = relative_error(run, *ref.trajectory).displacement;
      const bool finite = std::isfinite(r.max_drift_position) &&
                          std::isfinite(r.max_drift_velocity) &&
                          (!r.error || std::isfinite(*r.error));
      if (!finite) {
        r.status = "failed";
        r.reason = "the run finished with non-finite errors or drift";
      } else if (c.drift_limit) {
        r.status = r.max_drift_position <= *c.drift_limit ? "holds" : "inaccurate";
        if (r.status == "inaccurate") {
          std::ostringstream s;
          s << "position drift " << std::setprecision(2) << r.max_drift_position << " exceeds "
            << *c.drift_limit << " (this family is judged by its drift)";
          r.reason = s.str();
        }
      } else if (r.error && *r.error > kStressErrorFactor * r.rtol) {
        r.status = "inaccurate";
        std::ostringstream s;
        s << "error " << std::setprecision(2) << *r.error << " is " << std::setprecision(3)
          << *r.error / r.rtol << " x rtol (limit " << kStressErrorFactor << " x)";
        r.reason = s.str();
      } else {
        r.status = "holds";
      }
    }
  } catch (const SceneError& e) {
    r.status = "refused";
    r.reason = e.what();
  } catch (const SchemeNotApplicable& e) {
    r.status = "refused";
    r.reason = e.what();
  } catch (const std::exception& e) {
    // Not the integrator's failure: the formulation could not be set up for this scene (a
    // singular consistency system at t = 0, a massless master DOF).
    r.status = "refused";
    r.reason = e.what();
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace

std::vector<Scheme> stress_runs(const StressCase& c, const std::vector<Scheme>& asked) {
  std::vector<Scheme> out;
  const auto add = [&](Scheme s) {
    if (asked.empty() || std::find(asked.begin(), asked.end(), s) != asked.end()) out.push_back(s);
  };
  if (c.schemes.empty()) {
    for (Scheme s : kSchemes) add(s);
  } else {
    for (Scheme s : c.schemes) add(s);
  }
  return out;
}

StressResult run_stress(const StressOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  StressResult out;
  out.cases = stress_cases(options.families);
  // One task per (case, scheme); the references first, one per case.
  struct Task {
    std::size_t case_index;
    Scheme scheme;
    std::size_t slot;  ///< the record's place in the report: case order, then scheme order
  };
  std::vector<SceneSpec> specs;
  std::vector<Task> tasks;
  for (std::size_t i = 0; i < out.cases.size(); ++i) {
    const auto& c = out.cases[i];
    specs.push_back(parse_scene_text(c.scene_text, c.id));
    for (Scheme s : stress_runs(c, options.schemes)) tasks.push_back({i, s, tasks.size()});
  }
  // The longest runs first, so that two workers finish together.
  std::stable_sort(tasks.begin(), tasks.end(), [&](const Task& a, const Task& b) {
    return out.cases[a.case_index].max_steps > out.cases[b.case_index].max_steps;
  });
  std::vector<Reference> refs(out.cases.size());
  std::vector<StressRecord> records(tasks.size());
  std::mutex progress_mutex;
  std::size_t done = 0;
  const auto parallel = [&](std::size_t count, const std::function<void(std::size_t)>& work) {
    std::atomic<std::size_t> next{0};
    const auto worker = [&] {
      for (std::size_t k = next++; k < count; k = next++) work(k);
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::max(1, options.threads); ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
  };
  // A reference for each case that runs (--schemes can leave a case without runs).
  std::vector<bool> runs(out.cases.size(), false);
  for (const Task& t : tasks) runs[t.case_index] = true;
  parallel(out.cases.size(), [&](std::size_t i) {
    if (runs[i]) refs[i] = make_reference(specs[i]);
  });
  parallel(tasks.size(), [&](std::size_t k) {
    const Task& t = tasks[k];
    records[t.slot] =
        run_one(out.cases[t.case_index], specs[t.case_index], refs[t.case_index], t.scheme);
    if (options.progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      const auto& r = records[t.slot];
      std::ostringstream s;
      s << "[" << ++done << "/" << tasks.size() << "] " << r.family << " " << r.label << " "
        << to_string(r.scheme) << ": " << r.status;
      options.progress(s.str());
    }
  });
  out.records = std::move(records);
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace condyn
