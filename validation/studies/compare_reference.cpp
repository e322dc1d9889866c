#include "validation/studies/compare_reference.hpp"

#include "dae/run/mapped_rows.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "validation/references/accuracy.hpp"
#include "validation/references/exact_solution.hpp"
#include "validation/references/scientific.hpp"

namespace condyn {

SolveSpec settings_of(const SolveSpec& scene, Scheme scheme, double rtol, double atol) {
  SolveSpec s = scene;
  s.scheme = scheme;
  s.rtol = rtol;
  s.atol = atol;
  return s;
}

RunHooks progress_hooks(const CompareOptions& options, const std::string& what) {
  RunHooks hooks;
  if (!options.progress) return hooks;
  hooks.on_progress = [&options, what](const Progress& p) {
    std::ostringstream s;
    s.precision(4);
    s << what << ": running, t = " << p.t << " of " << p.t_end << ", " << p.steps << " steps, ";
    s.precision(3);
    s << p.elapsed_seconds << " s";
    options.progress(s.str());
  };
  return hooks;
}

namespace {

/// The settings of a reference run: the scene's with `scheme` at `rtol` (atol rtol/100),
/// without a budget ([solve] max_steps, max_wall_time; first_run says why) and without bridges
/// across singular configurations (a BDF reference is the scheme's alone, its error the
/// tolerance's; where it cannot pass one, newmark_reference, whose error is measured).
SolveSpec unbounded(const SolveSpec& settings, Scheme scheme, double rtol) {
  SolveSpec s = settings_of(settings, scheme, rtol, rtol * 1e-2);
  s.max_steps = 0;
  s.max_wall_time = 0.0;
  s.bridge_singular = false;
  return s;
}

/// A reference run: its scheme, its trajectory and how it was run ("at rtol 1.0e-12", or the
/// Newmark family's fixed step and its error estimate).
struct ReferenceRun {
  Scheme scheme = Scheme::ggl;
  Trajectory trajectory;
  std::string how;
};

/// Steps per output interval of the Newmark family's reference (on compare's refined grid,
/// kScaleSamples per output step): its error, O(h²), is then about 2.5e-4 of the one a step of the
/// interval would make (IFToMM A02, 20 s in output steps of 0.05: h = 1.95e-4, 1.7e-5 m from its
/// published reference, docs/cli.md).
constexpr int kNewmarkReferenceStepsPerOutput = 64;

/// Where every BDF reference failed (the IFToMM N-four-bar passes its singular positions under the
/// generalized-α family alone, docs/limitations.md): generalized_alpha with the scene's
/// parameters at a fixed step (Newton to `rtol`), the output interval over
/// kNewmarkReferenceStepsPerOutput, and again at twice that step. At order 2 their difference is
/// about three times the finer run's error: `how` reports that estimate, the reference's own
/// error, below which compare cannot tell a run's error from the reference's.
std::optional<ReferenceRun> newmark_reference(const Model& model, const SolveSpec& settings,
                                              const CompareOptions& options, double rtol,
                                              const std::string& what, std::string& failures) {
  const Scheme scheme = Scheme::generalized_alpha;
  if (scheme_refusal(model, scheme)) return std::nullopt;
  const double h = settings.output_step / kNewmarkReferenceStepsPerOutput;
  std::vector<Trajectory> runs;
  try {
    for (const double step : {h, 2.0 * h}) {
      // rtol and atol: the Newton iterations' tolerances under a fixed step
      SolveSpec fixed = unbounded(settings, scheme, rtol);
      fixed.step = step;
      runs.push_back(succeeded(solve(model, fixed,
                                     progress_hooks(options, what + " " + to_string(scheme) +
                                                                 " step " + scientific(step, 2))))
                         .trajectory);
    }
  } catch (const std::exception& why) {
    failures += (failures.empty() ? "" : "; ") + std::string(to_string(scheme)) + " at step " +
                scientific(h, 2) + ": " + why.what();
    return std::nullopt;
  }
  const TrajectoryError twice = relative_error(runs[1], runs[0]);
  ReferenceRun out{scheme, std::move(runs[0]),
                   "at the fixed step " + scientific(h, 2) + " (its own relative errors about u " +
                       scientific(twice.displacement / 3.0, 1) + ", u' " +
                       scientific(twice.velocity / 3.0, 1) + ", f_con " +
                       scientific(twice.reaction / 3.0, 1) +
                       ": a third of its differences from a run at twice the step)"};
  return out;
}

/// The first of elimination, GGL, projection and index1 that applies and reaches t_end at `rtol`
/// (atol rtol/100), without the scene's budget ([solve] max_steps, max_wall_time) as without
/// compare's: a reference at rtol/100 takes more steps than the runs it scores (the scene's 450
/// steps failed all three fallbacks of a nonlinear scene). Each in turn,
/// the next when one fails or does not apply: GGL at tight tolerances can ask its derived μ and λ
/// tolerances for roundoff (the pendulum at rtol 1e-13 failed, where projection and index1 run
/// it). When all fail, newmark_reference; nothing when that fails too, and `failures` then says
/// why, scheme by scheme.
std::optional<ReferenceRun> first_run(const Model& model, const SolveSpec& settings,
                                      const CompareOptions& options, double rtol,
                                      const std::string& what, std::string& failures) {
  for (Scheme scheme : {Scheme::elimination, Scheme::ggl, Scheme::projection, Scheme::index1}) {
    if (scheme_refusal(model, scheme)) continue;
    // A nonlinear model's reference stays GGL's, as before elimination treated such models:
    // coordinate partitioning at the reference's tolerance re-solves the constraints at every
    // evaluation of a dense-Jacobian ODE, far dearer on large mechanisms.
    if (scheme == Scheme::elimination && model.is_nonlinear()) continue;
    try {
      const SolveResult run = solve(
          model, unbounded(settings, scheme, rtol),
          progress_hooks(options, what + " " + to_string(scheme) + " rtol " + scientific(rtol, 1)));
      return ReferenceRun{scheme, succeeded(run).trajectory, "at rtol " + scientific(rtol, 1)};
    } catch (const std::exception& why) {
      failures +=
          (failures.empty() ? "" : "; ") + std::string(to_string(scheme)) + ": " + why.what();
    }
  }
  return newmark_reference(model, settings, options, rtol, what, failures);
}

/// The best reference available: a built-in benchmark's published state at t_end, else the exact
/// modal solution, else a tight run (first_run at 1/100 of the smallest tolerance). Trajectories
/// are at settings.output_times().
Trajectory reference(const Model& model, const SolveSpec& settings, const CompareOptions& options,
                     CompareResult& out) {
  if (model.reference) {
    if (const auto published = model.reference(settings.t_end)) {
      out.reference_kind = "published";
      out.reference_description = published->source;
      out.trusted_digits_u = published->digits_u;
      out.trusted_digits_v = published->digits_v;
      Trajectory ref;
      ref.t = {published->t};
      ref.u = published->u;
      ref.v = published->v;
      return ref;
    }
  }
  try {
    Trajectory exact = exact_trajectory(model, settings.output_times());
    out.reference_kind = "exact";
    out.reference_description = "exact modal solution (closed form)";
    return exact;
  } catch (const ExactSolutionUnavailable& e) {
    const double tight = std::max(
        1e-13, *std::min_element(options.tolerances.begin(), options.tolerances.end()) / 100.0);
    std::string failures;
    if (auto run = first_run(model, settings, options, tight, "reference", failures)) {
      out.reference_kind = to_string(run->scheme);
      out.reference_description = std::string(to_string(run->scheme)) + " " + run->how +
                                  " (no exact solution: " + e.what() +
                                  (failures.empty() ? "" : "; failed: " + failures) + ")";
      return std::move(run->trajectory);
    }
    // Without a reference no run can be scored: say which runs failed and what to change.
    throw NoReferenceError(
        "no reference solution: there is no exact one (" + std::string(e.what()) +
        "), and the tight reference runs failed at rtol " + scientific(tight, 1) +
        " (1/100 of the smallest --tolerances value): " + failures +
        "; a looser smallest tolerance, or a t_end the scene reaches, gives compare a "
        "reference (`condyn run` with --scheme ggl --rtol " +
        scientific(tight, 1) + " --atol " + scientific(tight * 1e-2, 1) + " shows the same)");
  }
}

/// The rows of `dense` at `times`, each of them among its times (the output grid refined by
/// kScaleSamples, whose every kScaleSamples-th time is an output time bit for bit).
Trajectory rows_at(const Trajectory& dense, const std::vector<double>& times) {
  std::vector<Eigen::Index> cols;
  std::size_t j = 0;
  for (double t : times) {
    while (j < dense.t.size() && dense.t[j] < t) ++j;
    if (j == dense.t.size() || dense.t[j] != t) {
      throw std::logic_error("compare: output time " + scientific(t, 16) +
                             " is not among the reference's times");
    }
    cols.push_back(static_cast<Eigen::Index>(j));
  }
  const auto pick = [&cols](const Eigen::MatrixXd& x) {
    return x.cols() == 0 ? x : Eigen::MatrixXd(x(Eigen::all, cols));
  };
  const auto pick_vector = [&cols](const Eigen::VectorXd& x) {
    return x.size() == 0 ? x : Eigen::VectorXd(x(cols));
  };
  Trajectory out;
  out.t = times;
  out.u = pick(dense.u);
  out.v = pick(dense.v);
  out.reaction = pick(dense.reaction);
  out.acceleration = pick(dense.acceleration);
  out.multiplier = pick(dense.multiplier);
  out.drift_position = pick_vector(dense.drift_position);
  out.drift_velocity = pick_vector(dense.drift_velocity);
  out.energy = pick_vector(dense.energy);
  out.kinetic = pick_vector(dense.kinetic);
  out.energy_scale = dense.energy_scale;
  if (!dense.near_singular.empty()) {
    for (const Eigen::Index c : cols) out.near_singular.push_back(dense.near_singular[c]);
  }
  return out;
}

/// The scene's settings with kScaleSamples output rows per output interval.
SolveSpec refined(SolveSpec settings) {
  settings.output_step /= kScaleSamples;  // a power of two: the output times stay among its own
  return settings;
}

/// The error scales (accuracy.hpp) of a run against a published state, which has no trajectory:
/// from a run of first_run at drift_rtol on the refined grid (two digits of a scale need no
/// tight run), or, when all fail, nothing (each run's own rows then give its scales).
std::optional<ErrorScales> published_scales(const Model& model, const SolveSpec& settings,
                                            const CompareOptions& options, std::string& source) {
  std::string failures;
  if (auto run =
          first_run(model, refined(settings), options, options.drift_rtol, "scales", failures)) {
    source = std::string("a ") + to_string(run->scheme) + " run " + run->how;
    return error_scales(run->trajectory);
  }
  source = "each run's own output rows (the scale runs failed: " + failures + ")";
  return std::nullopt;
}

}  // namespace

Trajectory reference_at_rows(const Model& base, const SolveSpec& scene,
                             const CompareOptions& options, CompareResult& out) {
  // A mechanism's reference in its output map's columns, as its runs are scored (a published
  // state, of a built-in model, has no map).
  const Trajectory dense =
      mapped_trajectory(base, reference(base, refined(scene), options, out), {}, true);
  const bool published = out.reference_kind == "published";
  std::optional<ErrorScales> scales;
  if (published) {
    scales = published_scales(base, scene, options, out.scale_source);
  } else {
    scales = error_scales(dense);
    out.scale_source = "the reference";
  }
  if (scales) out.error_scales = *scales;
  Trajectory ref = published ? dense : rows_at(dense, scene.output_times());
  if (!published) {
    out.reference_t = ref.t;
    out.reference_multiplier = ref.multiplier;
  }
  return ref;
}

}  // namespace condyn
