// condyn check: run scenes and evaluate their [[check]] tables (docs/checks.md).

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

#include "dae/interface/scheme_not_applicable.hpp"
#include "models/scene/scene_parser.hpp"
#include "src/cli/cli_flags.hpp"
#include "src/cli/commands.hpp"
#include "src/output/output_files.hpp"
#include "src/output/output_format.hpp"
#include "src/reports/check_report.hpp"
#include "validation/studies/user_checks.hpp"

namespace condyn {

namespace {

struct CheckArgs {
  std::vector<std::string> scenes;
  std::string scheme, junit;
  std::optional<double> step;  ///< --step: the Newmark family's fixed step
};

/// One scene run and its checks evaluated, timed; what goes wrong is recorded with its exit code
/// (2 bad input, 1 a failure), not thrown.
CheckedScene check_scene(const std::string& path, const SceneCheckOptions& options) {
  CheckedScene c;
  c.scene = path;
  const auto start = std::chrono::steady_clock::now();
  try {
    c.result = run_scene_checks(path, options);
    c.exit_code = exit_code_of(*c.result);
  } catch (const SceneError& e) {
    c.error = e.what();
    c.exit_code = 2;
  } catch (const SchemeNotApplicable& e) {
    c.error = scene_message(path, e.where(), e.what());
    c.exit_code = 2;
  } catch (const std::exception& e) {
    c.error = path + ": " + e.what();
    c.exit_code = 1;
  }
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return c;
}

/// condyn check: every scene run and its [[check]] tables evaluated; the exit code is the worst
/// of the scenes' (0 all hold, 1 a check or a run failed, 2 bad input).
int check(const std::vector<std::string>& scenes, const std::string& scheme,
          std::optional<double> step, const std::string& junit) {
  SceneCheckOptions options;
  options.step = step;
  if (!scheme.empty()) {
    options.scheme = parse_scheme_flag("--scheme", scheme);
    options.scheme_where = {"--scheme", 0};
  }
  OutputPlan plan;  // the JUnit report, checked before the runs
  for (const auto& s : scenes) plan.add_input(s);
  std::optional<OutputPlan::Id> report;
  if (!junit.empty()) {
    // Nor may it be a file a scene reads (a matrix, a table, a check's reference): each scene is
    // parsed for their names first (a scene that does not parse is reported by its run below).
    for (const auto& s : scenes) {
      try {
        for (const auto& input : parse_scene_file(s).input_files) plan.add_input(input);
      } catch (const std::exception&) {  // the run below reports it
      }
    }
    report = plan.add_output(junit, "--junit");
  }
  plan.check();
  if (report) (void)output_format(junit, "--junit", {FileFormat::xml});  // its name says XML
  // A report on standard output (`--junit -`) keeps it a well-formed XML stream: the lines go to
  // stderr, as run's do with `--out -`.
  std::ostream& msg = report && plan.to_stdout(*report) ? std::cerr : std::cout;
  std::vector<CheckedScene> checked;
  int code = 0;
  for (const auto& path : scenes) {
    CheckedScene c = check_scene(path, options);
    print_checked_scene(msg, c);
    // On disk before the next scene runs: a CI job killed by its time limit keeps the verdicts
    // already reached (stdout to a file or pipe is fully buffered, and a signal discards it).
    msg.flush();
    code = std::max(code, c.exit_code);
    checked.push_back(std::move(c));
  }
  print_check_summary(msg, checked);
  if (report) {
    plan.write(*report, [&checked](std::ostream& out) { out << junit_xml(checked); });
    plan.commit_all();
    msg << "wrote the JUnit report to " << plan.display_name(*report) << "\n";
  }
  return code;
}

}  // namespace

Command add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  auto* cmd = app.add_subcommand(
      "check", "run scenes and evaluate their [[check]] tables: exit 0 only if every check holds");
  cmd->add_option("scenes", args->scenes, "scene files (TOML) with [[check]] tables")->required();
  cmd->add_option("--scheme", args->scheme,
                  "scheme for every scene (overrides [solve] scheme): " + scheme_names())
      ->check(non_empty_check());
  add_step_option(cmd, args->step);
  cmd->add_option("--junit", args->junit,
                  "also write a JUnit XML report to this file (.xml or no extension)")
      ->check(non_empty_check());
  return {cmd, [args] { return check(args->scenes, args->scheme, args->step, args->junit); }};
}

}  // namespace condyn
