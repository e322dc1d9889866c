#include "validation/references/suite.hpp"

#include <iomanip>
#include <sstream>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/references/benchmark_suite.hpp"
#include "validation/references/chapter_report.hpp"
#include "validation/references/embedded_scenes.hpp"
#include "validation/references/exact_solution.hpp"
#include "validation/references/scientific.hpp"

namespace condyn {

namespace {}  // namespace

bool run_validation(std::ostream& out, const ValidationOptions& options) {
  const ChapterReport chapter = chapter_report();
  bool all_pass = true;
  std::ostringstream summary_table;
  out << "condyn validate: the chapter's example truss, five cases (§5.5.1-§5.6.2)\n"
      << "errors are relative max-norms over all DOFs and output times against the exact modal\n"
      << "solution; tolerance = " << kGlobalErrorFactor << " x rtol\n\n";
  for (const auto& cr : chapter.cases) {
    const std::string file = "<embedded:" + cr.scene + ">";
    const SceneSpec spec = parse_scene_text(embedded_scene(cr.scene).text, file);
    const Model model = build_model(spec);
    out << "== " << cr.section << ": " << model.name << "\n";
    if (!options.quiet) print_case_matrices(out, cr);
    const Trajectory exact = exact_trajectory(model, spec.solve.output_times());
    out << "  " << std::left << std::setw(13) << "scheme" << std::setw(10) << "rtol"
        << std::setw(11) << "err u" << std::setw(11) << "err v" << std::setw(11) << "err f_con"
        << std::setw(11) << "max drift" << std::setw(8) << "steps" << std::setw(10) << "time ms"
        << "verdict\n";
    for (Scheme scheme : kValidatedSchemes) {
      SolveSpec settings = spec.solve;
      settings.scheme = scheme;
      const SolveResult result = solve(model, settings);
      const Trajectory& run = succeeded(result).trajectory;
      const SolveSummary& summary = result.summary;
      const TrajectoryError err = relative_error(run, exact);
      const double tol = kGlobalErrorFactor * spec.solve.rtol;
      const bool pass = err.worst() <= tol;
      all_pass = all_pass && pass;
      const double drift = std::max(summary.max_drift_position, summary.max_drift_velocity);
      out << "  " << std::left << std::setw(13) << to_string(scheme) << std::setw(10)
          << scientific(spec.solve.rtol, 2) << std::setw(11) << scientific(err.displacement, 2)
          << std::setw(11) << scientific(err.velocity, 2) << std::setw(11)
          << scientific(err.reaction, 2) << std::setw(11) << scientific(drift, 2) << std::setw(8)
          << summary.steps << std::setw(10) << std::fixed << std::setprecision(2)
          << summary.wall_seconds * 1e3 << std::defaultfloat << (pass ? "pass" : "FAIL") << "\n";
      // setw counts bytes; "§" takes two.
      summary_table << "  " << std::left << std::setw(10) << cr.section << std::setw(13)
                    << to_string(scheme) << std::setw(11) << scientific(err.displacement, 2)
                    << std::setw(11) << scientific(err.velocity, 2) << std::setw(11)
                    << scientific(err.reaction, 2) << std::setw(11) << scientific(tol, 2)
                    << std::setw(8) << summary.steps << (pass ? "pass" : "FAIL") << "\n";
    }
    out << "\n";
  }
  out << "Summary (errors against the exact modal solution, relative max-norm):\n"
      << "  " << std::left << std::setw(9) << "case" << std::setw(13) << "scheme" << std::setw(11)
      << "err u" << std::setw(11) << "err v" << std::setw(11) << "err f_con" << std::setw(11)
      << "tolerance" << std::setw(8) << "steps"
      << "verdict\n"
      << summary_table.str() << "\n";
  print_errata(out, chapter.errata);
  out << "\n";
  all_pass = run_published_benchmarks(out) && all_pass;
  out << (all_pass ? "validation passed" : "validation FAILED") << "\n";
  return all_pass;
}

}  // namespace condyn
