// condyn: constrained dynamic systems with constraints as algebraic equations.
// Commands: run, info, validate, compare, stress. See README.md.

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "dae/ida_integrator.hpp"
#include "dae/solve.hpp"
#include "models/scene_parser.hpp"
#include "src/compare_output.hpp"
#include "src/csv_output.hpp"
#include "src/info_report.hpp"
#include "src/report_format.hpp"
#include "src/stress_output.hpp"
#include "validation/accuracy.hpp"
#include "validation/compare.hpp"
#include "validation/embedded_scenes.hpp"
#include "validation/stress.hpp"
#include "validation/suite.hpp"

namespace {

using namespace condyn;

Scheme parse_scheme_flag(const std::string& s) {
  if (const auto scheme = scheme_from_string(s)) return *scheme;
  throw CLI::ValidationError("--scheme",
                             "unknown scheme '" + s + "' (expected " + scheme_names() + ")");
}

/// FILE.csv -> FILE.partial.csv (beside it): where a failed run keeps what it computed, so that
/// the file the user named is never overwritten by an incomplete result.
std::string partial_path(const std::string& out) {
  const std::filesystem::path p(out);
  return (p.parent_path() / (p.stem().string() + ".partial" + p.extension().string())).string();
}

/// The message for a failed run: what failed where, what to try, and where the rows computed
/// before the failure went (written here, so nothing computed is lost).
std::string describe_failure(const IntegrationError& e, const Model& model,
                             const std::string& out) {
  std::ostringstream s;
  s << "under " << (e.scheme.empty() ? "the requested scheme" : e.scheme) << ": " << e.what();
  if (e.in_loop) {
    s << "\n  reached t = " << e.t_reached << " of t_end = " << model.solve.t_end << ", last step "
      << e.last_step;
  }
  if (!e.suggestion.empty()) s << "\n  suggestion: " << e.suggestion;
  if (e.partial) {
    const std::string partial = partial_path(out);
    try {
      write_csv_atomically(partial, model, *e.partial);
      s << "\n  partial result: the " << e.partial->t.size()
        << " output rows up to t = " << e.partial->t.back() << " are in " << partial
        << " (the run did not reach t_end; " << out << " was not written)";
    } catch (const std::exception& write_error) {
      s << "\n  the partial result could not be written: " << write_error.what();
    }
  }
  return s.str();
}

struct RunArgs {
  std::string scene, scheme, out, steps_out;
  std::optional<double> rtol, atol;
};

int run(const RunArgs& args) {
  SceneSpec spec = parse_scene_file(args.scene);
  if (!args.scheme.empty()) spec.solve.scheme = parse_scheme_flag(args.scheme);
  if (args.rtol) spec.solve.rtol = *args.rtol;
  if (args.atol) spec.solve.atol = *args.atol;
  const Model model = build_model(spec);
  std::string out = args.out.empty() ? model.output.file : args.out;
  if (out.empty()) out = std::filesystem::path(args.scene).stem().string() + ".csv";

  const SchemeChoice choice = choose_scheme(model, spec.solve.scheme);
  SolveSummary summary;
  IntegratorOptions options = integrator_options(model);
  options.record_steps = !args.steps_out.empty();
  Trajectory traj;
  try {
    traj = solve(model, choice.scheme, options, summary);
  } catch (const IntegrationError& e) {
    throw IntegrationError(describe_failure(e, model, out));
  }
  write_csv_atomically(out, model, traj);
  if (!model.initial_projection.empty())
    std::cout << "initial state: " << model.initial_projection << "\n";
  for (const auto& w : model.warnings) std::cerr << "warning: " << args.scene << ": " << w << "\n";
  for (const auto& d : model.dropped_constraints)
    std::cout << "dropped redundant constraint " << d << "\n";
  std::cout << summary.brief() << "\n";
  if (const double e = relative_energy_error(model, traj); e >= 0.0) {
    std::cout << "energy: max |E(t) - E(0)| = " << e
              << " relative to max(|E(0)|, max kinetic energy)\n";
  }
  if (const auto score = score_against_reference(model, traj, options.rtol, options.atol)) {
    std::cout << "published reference at t = " << score->t << " (" << score->source
              << "): " << score->describe() << " (mescd with rtol " << options.rtol << ", atol "
              << options.atol << ")\n";
  }
  std::cout << "wrote " << traj.t.size() << " rows to " << out << "\n";
  if (!args.steps_out.empty()) {
    write_steps_csv_atomically(args.steps_out, traj);
    std::cout << "wrote the drift at " << traj.steps.size() << " internal steps to "
              << args.steps_out << "\n";
  }
  return 0;
}

/// Splits "a,b,c" (spaces ignored).
std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::string item;
  for (char c : s + ",") {
    if (c == ',') {
      if (!item.empty()) out.push_back(item);
      item.clear();
    } else if (c != ' ') {
      item += c;
    }
  }
  return out;
}

int compare(const std::string& scene, std::string dir, const std::string& tolerances,
            const std::string& schemes, bool no_plots, CompareOptions options) {
  const std::string stem =
      scene.empty() ? "chapter_5_5_1" : std::filesystem::path(scene).stem().string();
  const SceneSpec spec =
      scene.empty() ? parse_scene_text(embedded_scene(stem).text, "<embedded:" + stem + ">")
                    : parse_scene_file(scene);
  if (dir.empty()) dir = "condyn-out/compare-" + stem;
  if (!tolerances.empty()) {
    options.tolerances.clear();
    for (const auto& t : split_list(tolerances)) {
      try {
        options.tolerances.push_back(std::stod(t));
      } catch (const std::exception&) {
        throw CLI::ValidationError("--tolerances", "'" + t + "' is not a number");
      }
    }
  }
  if (!schemes.empty()) {
    options.schemes.clear();
    for (const auto& s : split_list(schemes)) {
      const Scheme scheme = parse_scheme_flag(s);
      if (scheme == Scheme::automatic) {
        throw CLI::ValidationError("--schemes", "name schemes, not 'auto'");
      }
      options.schemes.push_back(scheme);
    }
  }
  try {
    options.validate();
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("compare", e.what());
  }
  options.progress = [](const std::string& line) { std::cerr << line << std::endl; };
  const CompareResult result = run_compare(spec, options);
  print_compare_table(std::cout, result);
  write_compare_files(dir, result);
  std::cout << "\nwrote runs.csv, runs.json, drift_*.csv, history_*.csv, baumgarte_study.csv and "
               "summary.txt to "
            << dir << "\n";
  if (!no_plots) std::cout << draw_compare_plots(dir) << "\n";
  return 0;
}

int stress(std::string dir, const std::string& families, bool no_plots) {
  StressOptions options;
  for (const auto& f : split_list(families)) options.families.push_back(f);
  try {
    (void)stress_cases(options.families);  // unknown family names are usage errors
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--families", e.what());
  }
  if (dir.empty()) dir = "condyn-out/stress";
  options.progress = [](const std::string& line) { std::cerr << line << std::endl; };
  const StressResult result = run_stress(options);
  print_stress_report(std::cout, result);
  write_stress_files(dir, result);
  std::cout << "\nwrote stress.csv, stress.json, summary.txt and scenes/*.toml to " << dir << "\n";
  if (!no_plots) std::cout << run_plot_script("plot_stress.py", dir) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"condyn: constrained dynamic systems, constraints as algebraic equations"};
  app.require_subcommand(1);

  RunArgs run_args;
  auto* run_cmd = app.add_subcommand("run", "solve a scene and write its CSV");
  run_cmd->add_option("scene", run_args.scene, "scene file (TOML)")->required();
  run_cmd->add_option("--scheme", run_args.scheme,
                      "scheme (overrides [solve] scheme): " + scheme_names());
  // CLI::PositiveNumber lets nan and inf through (nan <= 0 is false): a tolerance must be a
  // finite number > 0, like [solve] rtol and atol.
  const CLI::Validator finite_positive(
      [](std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || !(v > 0.0)) {
          return "must be a finite number > 0 (got '" + text + "')";
        }
        return {};
      },
      "FINITE > 0");
  run_cmd->add_option("--rtol", run_args.rtol, "relative tolerance (overrides [solve] rtol)")
      ->check(finite_positive);
  run_cmd->add_option("--atol", run_args.atol, "absolute tolerance (overrides [solve] atol)")
      ->check(finite_positive);
  run_cmd->add_option("--out", run_args.out,
                      "CSV file (default: [output] file, else SCENE-STEM.csv here)");
  run_cmd->add_option("--steps-out", run_args.steps_out,
                      "also write the constraint drift at every internal step to this CSV");

  std::string info_scene, info_scheme;
  auto* info_cmd = app.add_subcommand("info", "classify the constraints and size the model");
  info_cmd->add_option("scene", info_scene, "scene file (TOML)")->required();
  info_cmd->add_option("--scheme", info_scheme, "scheme to report on (default: the scene's)");

  std::string compare_scene, compare_dir, compare_tolerances, compare_schemes;
  bool compare_no_plots = false;
  CompareOptions compare_options;
  auto* compare_cmd = app.add_subcommand(
      "compare", "every scheme across a tolerance sweep: errors, drift, cost, plots");
  compare_cmd->add_option("scene", compare_scene,
                          "scene file (default: the chapter truss, §5.5.1, built in)");
  compare_cmd->add_option("--out-dir", compare_dir,
                          "output folder (default: condyn-out/compare-SCENE-STEM)");
  compare_cmd->add_option("--tolerances", compare_tolerances,
                          "comma-separated rtol values (default 1e-3,1e-4,...,1e-10)");
  compare_cmd->add_option("--schemes", compare_schemes,
                          "comma-separated schemes (default: all of them)");
  compare_cmd->add_option("--repeats", compare_options.repeats, "runs per point for the wall time")
      ->check(CLI::Range(1, 100));
  compare_cmd
      ->add_option("--drift-rtol", compare_options.drift_rtol,
                   "tolerance of the drift, history and Baumgarte-study runs")
      ->check(CLI::Range(1e-14, 0.5));
  compare_cmd->add_flag("--no-plots", compare_no_plots, "do not call the plotting script");

  std::string stress_dir, stress_families_list;
  bool stress_no_plots = false;
  auto* stress_cmd = app.add_subcommand(
      "stress", "stiff and extreme generated scenes under every scheme: where each holds, breaks");
  stress_cmd->add_option("--out-dir", stress_dir, "output folder (default: condyn-out/stress)");
  stress_cmd->add_option("--families", stress_families_list,
                         "comma-separated families (default: all): stiffness, mass_ratio, "
                         "penalty_weight, baumgarte_gains, long_horizon, redundancy, dead_point, "
                         "high_frequency");
  stress_cmd->add_flag("--no-plots", stress_no_plots, "do not call the plotting script");

  ValidationOptions validate_options;
  auto* validate_cmd = app.add_subcommand("validate", "run the built-in validation suite");
  validate_cmd->add_flag("--quiet", validate_options.quiet, "print only the summary tables");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints and succeeds; every other command-line error is a usage error: exit 2, as the
    // contract says (CLI11's own codes are 100+).
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  // The scene being processed, to name it in errors that arise after parsing.
  const std::string scene = *run_cmd ? run_args.scene : *info_cmd ? info_scene : compare_scene;
  try {
    if (*run_cmd) return run(run_args);
    if (*info_cmd) {
      SceneSpec spec = parse_scene_file(info_scene);
      if (!info_scheme.empty()) spec.solve.scheme = parse_scheme_flag(info_scheme);
      print_info(std::cout, build_model(spec), spec.solve.scheme);
      return 0;
    }
    if (*validate_cmd) return run_validation(std::cout, validate_options) ? 0 : 1;
    if (*stress_cmd) return stress(stress_dir, stress_families_list, stress_no_plots);
    if (*compare_cmd) {
      return compare(compare_scene, compare_dir, compare_tolerances, compare_schemes,
                     compare_no_plots, compare_options);
    }
  } catch (const SceneError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const CLI::ValidationError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const SchemeNotApplicable& e) {
    std::cerr << "error: " << scene << ": " << e.what() << "\n";
    return 2;
  } catch (const IntegrationError& e) {
    std::cerr << "error: " << scene << ": integration failed: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << (scene.empty() ? "" : scene + ": ") << e.what() << "\n";
    return 1;
  }
  return 0;
}
