#include "src/reports/compare_output.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "src/reports/report_format.hpp"
#include "validation/references/scientific.hpp"

namespace condyn {

namespace {

std::string sci(double v, int digits = 2) {
  if (std::isnan(v)) return "-";  // not measured (e.g. reactions against a published state)
  return scientific(v, digits);
}

/// Fields of a run in the column order of runs.csv; failed runs leave the numbers empty.
ReportFields fields(const RunRecord& r) {
  auto num = [&](double v) { return r.ok && std::isfinite(v) ? full_precision(v) : std::string(); };
  auto count = [&](long v) { return r.ok ? std::to_string(v) : std::string(); };
  return {{"scheme", to_string(r.scheme)},
          {"rtol", full_precision(r.rtol)},
          {"atol", full_precision(r.atol)},
          {"status", r.ok ? "ok" : "failed"},
          {"error_u", num(r.error_u)},
          {"error_v", num(r.error_v)},
          {"error_reaction", num(r.error_reaction)},
          {"max_drift_position", num(r.max_drift_position)},
          {"max_drift_velocity", num(r.max_drift_velocity)},
          {"final_drift_position", num(r.final_drift_position)},
          {"final_drift_velocity", num(r.final_drift_velocity)},
          {"steps", count(r.steps)},
          {"residual_evals", count(r.residual_evals)},
          {"jacobian_evals", count(r.jacobian_evals)},
          {"newton_failures", count(r.newton_failures)},
          {"error_test_failures", count(r.error_test_failures)},
          {"wall_median_s", num(r.wall_median)},
          {"wall_min_s", num(r.wall_min)},
          {"wall_max_s", num(r.wall_max)},
          {"repeats", count(r.repeats)},
          {"message", r.message},
          {"mescd_u", num(r.mescd_u)},
          {"mescd_v", num(r.mescd_v)},
          {"energy_error", num(r.energy_error)},
          // NaN: no target (the Newmark family under a fixed step, validation/studies/compare.cpp).
          {"error_target", std::isfinite(r.error_target) ? full_precision(r.error_target) : ""},
          {"error_ratio", num(r.error_ratio)},
          {"over_tolerance", r.ok ? (r.over_tolerance ? "1" : "0") : std::string()}};
}

}  // namespace

namespace {

/// The header's statement of what the errors are relative to, with the scales.
std::string error_scales_line(const CompareResult& result) {
  const ErrorScales& s = result.error_scales;
  const bool published = result.reference_kind == "published";
  std::string text = published ? "errors: max-norm over all DOFs at the reference's time"
                               : "errors: max-norm over all DOFs and output times";
  if (result.scale_source.rfind("each run", 0) == 0) {
    return text + ", relative to the reference's largest value, else to " + result.scale_source;
  }
  text += ", relative to the largest value over the whole run of " + result.scale_source +
          " (sampled " + std::to_string(kScaleSamples) + " times per output step): |u| " +
          sci(s.displacement, 1) + ", |u'| " + sci(s.velocity, 1);
  if (!published) text += ", |f_con| " + sci(s.reaction, 1);
  if (s.energy > 0.0) text += ", energy " + sci(s.energy, 1);
  return text;
}

/// The sweep's table: one row per run, the optional columns (digits, energy) only when some run
/// has them.
void print_runs(std::ostream& out, const CompareResult& result) {
  const auto any = [&](auto has) {
    return std::any_of(result.runs.begin(), result.runs.end(), has);
  };
  const bool digits = any([](const RunRecord& r) { return std::isfinite(r.mescd_u); });
  const bool energy = any([](const RunRecord& r) { return std::isfinite(r.energy_error); });
  std::vector<std::string> header = {"scheme",    "rtol",       "err u",     "err v",
                                     "err f_con", "err/target", "max drift", "end drift",
                                     "steps",     "res",        "jac",       "wall ms (min-max)"};
  if (digits) header.insert(header.end(), {"digits u", "digits v"});
  if (energy) header.emplace_back("energy err");
  header.emplace_back("mark");
  TextTable table(header);
  const auto fixed = [](double v, int decimals) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << v;
    return s.str();
  };
  for (const auto& r : result.runs) {
    std::vector<std::string> row = {to_string(r.scheme), sci(r.rtol, 0)};
    if (!r.ok) {
      row.push_back("FAILED: " + r.message);
      table.add_row(std::move(row));
      continue;
    }
    row.insert(row.end(), {sci(r.error_u, 1), sci(r.error_v, 1), sci(r.error_reaction, 1),
                           sci(r.error_ratio, 1), sci(r.max_drift_position, 1),
                           sci(r.final_drift_position, 1), std::to_string(r.steps),
                           std::to_string(r.residual_evals), std::to_string(r.jacobian_evals),
                           fixed(r.wall_median * 1e3, 2) + " (" + fixed(r.wall_min * 1e3, 2) + "-" +
                               fixed(r.wall_max * 1e3, 2) + ")"});
    if (digits) {
      row.push_back(std::isfinite(r.mescd_u) ? fixed(r.mescd_u, 1) : "-");
      row.push_back(std::isfinite(r.mescd_v) ? fixed(r.mescd_v, 1) : "-");
    }
    if (energy) row.push_back(sci(r.energy_error, 1));
    row.emplace_back(r.over_tolerance ? "OVER" : "");
    table.add_row(std::move(row));
  }
  table.print(out);
  out << "\nerr/target: the worst of err u, err v, err f_con over the run's target, its rtol "
         "(under "
         "penalty, whose weight sets its error, max(rtol, "
      << sci(kPenaltyAccuracy, 0)
      << " x default weight / weight); none under a fixed step (the Newmark family, "
         "rattle), which sets its error); mark OVER: above "
      << sci(result.options.mark_factor, 0) << " (--fail-above)\n";
  if (const int over = result.over_tolerance_runs(); over > 0) {
    out << over << " run" << (over == 1 ? "" : "s")
        << " over tolerance: the errors are far beyond what rtol asks for\n";
  }
}

void print_drift_growth(std::ostream& out, const CompareResult& result) {
  out << "\ndrift growth at rtol " << sci(result.options.drift_rtol, 0)
      << " (position drift ~ t^p, fitted to its running max where it follows a steady law):\n";
  TextTable table({}, "  ");
  for (const auto& h : result.histories) {
    if (!h.ok) {
      table.add_row({to_string(h.scheme), "not fitted: the run failed"});
    } else if (h.growth.fit) {
      std::ostringstream p;
      p << "p = " << std::fixed << std::setprecision(2) << h.growth.fit->exponent;
      table.add_row(
          {to_string(h.scheme), p.str(),
           "over t in [" + sci(h.growth.fit->t_from, 1) + ", " + sci(h.growth.fit->t_to, 1) + "]",
           "theory: " + predicted_drift_growth(h.scheme)});
    } else {
      table.add_row({to_string(h.scheme), "not fitted: " + h.growth.reason});
    }
  }
  table.print(out);
}

void print_baumgarte_study(std::ostream& out, const CompareResult& result) {
  out << "\nBaumgarte study at rtol " << sci(result.options.drift_rtol, 0)
      << " (max position drift, steps; * = default gains):\n";
  TextTable table({"alpha", "beta", "", "drift", "steps"}, "  ");
  for (const auto& p : result.baumgarte_study) {
    std::vector<std::string> row = {sci(p.alpha, 2), sci(p.beta, 2), p.is_default ? "*" : ""};
    if (p.ok) {
      row.insert(row.end(), {sci(p.max_drift_position, 1), std::to_string(p.steps)});
    } else {
      row.push_back("FAILED: " + p.message);
    }
    table.add_row(std::move(row));
  }
  table.print(out);
}

}  // namespace

void print_compare_table(std::ostream& out, const CompareResult& result) {
  const bool published = result.reference_kind == "published";
  out << "scene: " << result.scene_name << "\nreference: " << result.reference_description << "\n"
      << error_scales_line(result) << "; wall: median of " << result.options.repeats
      << " runs (min-max)\n";
  for (const auto& [scheme, why] : result.skipped) {
    out << "not run: " << to_string(scheme) << " (" << why << ")\n";
  }
  out << "\n";
  print_runs(out, result);
  if (published) {
    out << "\ndigits: the test set's mescd at t_end (positions u, velocities v); the reference "
           "vouches for "
        << result.trusted_digits_u << " digits in u and " << result.trusted_digits_v
        << " in v: more is agreement at the reference's limit\n";
  }
  if (!result.histories.empty()) print_drift_growth(out, result);
  if (!result.baumgarte_study.empty()) print_baumgarte_study(out, result);
}

namespace {

const char* const kOutDir = "--out-dir";

std::string drift_file(Scheme s) { return std::string("drift_") + to_string(s) + ".csv"; }
std::string history_file(Scheme s) { return std::string("history_") + to_string(s) + ".csv"; }

}  // namespace

void plan_compare_files(OutputPlan& plan, const std::string& dir,
                        const std::vector<Scheme>& schemes, bool baumgarte_study) {
  namespace fs = std::filesystem;
  plan.add_folder(dir, kOutDir);
  const fs::path base(dir);
  for (const char* name : {"runs.csv", "runs.json", "summary.txt"}) {
    (void)plan.add_output((base / name).string(), kOutDir);
  }
  if (baumgarte_study) (void)plan.add_output((base / "baumgarte_study.csv").string(), kOutDir);
  (void)plan.add_output((base / "history_reference.csv").string(), kOutDir);
  for (Scheme s : schemes) {
    (void)plan.add_output((base / drift_file(s)).string(), kOutDir);
    (void)plan.add_output((base / history_file(s)).string(), kOutDir);
  }
}

void write_compare_files(const std::string& dir, const CompareResult& result) {
  OutputPlan plan;
  write_compare_files(plan, dir, result);
}

namespace {

/// runs.json: the reference and its scales, skipped schemes, drift growth, histories, the
/// options, and the runs (`rows`, runs.csv's fields).
void write_runs_json(std::ostream& out, const CompareResult& result,
                     const std::vector<ReportFields>& rows) {
  out << "{\n  \"scene\": " << json_string(result.scene_name)
      << ",\n  \"reference\": {\"kind\": " << json_string(result.reference_kind)
      << ", \"description\": " << json_string(result.reference_description);
  if (result.reference_kind == "published") {
    out << ", \"trusted_digits_u\": " << result.trusted_digits_u
        << ", \"trusted_digits_v\": " << result.trusted_digits_v;
  }
  const ErrorScales& sc = result.error_scales;
  out << ", \"scales\": {\"displacement\": " << full_precision(sc.displacement)
      << ", \"velocity\": " << full_precision(sc.velocity)
      << ", \"reaction\": " << full_precision(sc.reaction)
      << ", \"energy\": " << full_precision(sc.energy)
      << ", \"source\": " << json_string(result.scale_source) << "}";
  out << "},\n  \"skipped\": [";
  for (std::size_t k = 0; k < result.skipped.size(); ++k) {
    out << (k ? ", " : "") << "{\"scheme\": " << json_string(to_string(result.skipped[k].first))
        << ", \"reason\": " << json_string(result.skipped[k].second) << "}";
  }
  out << "],\n  \"drift_growth\": {";
  bool first_growth = true;
  for (const auto& h : result.histories) {
    const std::string reason = h.ok ? h.growth.reason : "the run failed";
    out << (first_growth ? "" : ", ") << json_string(to_string(h.scheme))
        << ": {\"exponent\": " << (h.growth.fit ? full_precision(h.growth.fit->exponent) : "null")
        << ", \"predicted\": " << json_string(predicted_drift_growth(h.scheme))
        << ", \"not_fitted_because\": " << (h.growth.fit ? "null" : json_string(reason)) << "}";
    first_growth = false;
  }
  out << "},\n  \"histories\": {";
  for (std::size_t k = 0; k < result.histories.size(); ++k) {
    const auto& h = result.histories[k];
    out << (k ? ", " : "") << json_string(to_string(h.scheme))
        << ": {\"status\": " << (h.ok ? "\"ok\"" : "\"failed\"")
        << ", \"t_reached\": " << full_precision(h.t_reached)
        << ", \"message\": " << json_string(h.message) << "}";
  }
  out << "},\n  \"tolerances\": [";
  for (std::size_t k = 0; k < result.options.tolerances.size(); ++k) {
    out << (k ? ", " : "") << full_precision(result.options.tolerances[k]);
  }
  out << "],\n  \"repeats\": " << result.options.repeats
      << ",\n  \"drift_rtol\": " << full_precision(result.options.drift_rtol)
      << ",\n  \"mark_factor\": " << full_precision(result.options.mark_factor)
      << ",\n  \"runs\": [\n";
  write_json_records(out, rows, {"scheme", "status", "message"}, "    ");
  out << "  ]\n}\n";
}

/// drift_<scheme>.csv: the drift at every internal step of a history run.
void write_drift_csv(std::ostream& out, const SchemeHistory& h) {
  out.precision(17);
  out << "t,drift_position,drift_velocity\n";
  for (const auto& s : h.trajectory.steps) {
    out << s.t << "," << s.drift_position << "," << s.drift_velocity << "\n";
  }
}

/// history_<scheme>.csv: a history run's multipliers and constrained DOFs' reactions at its rows.
void write_history_csv(std::ostream& out, const CompareResult& result, const SchemeHistory& h) {
  out.precision(17);
  const auto& tr = h.trajectory;
  out << "t";
  for (const auto& name : result.constraint_names) out << ",lambda_" << name;
  for (const auto& [name, index] : result.reaction_columns) out << "," << name;
  out << "\n";
  for (std::size_t k = 0; k < tr.t.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    out << tr.t[k];
    for (Eigen::Index i = 0; i < tr.multiplier.rows(); ++i) out << "," << tr.multiplier(i, col);
    for (const auto& [name, index] : result.reaction_columns) {
      out << "," << tr.reaction(index, col);
    }
    out << "\n";
  }
}

/// history_reference.csv: the reference's multipliers at its times.
void write_reference_history_csv(std::ostream& out, const CompareResult& result) {
  out.precision(17);
  out << "t";
  for (const auto& name : result.constraint_names) out << ",lambda_" << name;
  out << "\n";
  const Eigen::MatrixXd& lambda = result.reference_multiplier;
  for (std::size_t k = 0; k < result.reference_t.size(); ++k) {
    out << result.reference_t[k];
    for (Eigen::Index i = 0; i < lambda.rows(); ++i) {
      out << "," << lambda(i, static_cast<Eigen::Index>(k));
    }
    out << "\n";
  }
}

/// baumgarte_study.csv: one row per pair of gains.
void write_baumgarte_csv(std::ostream& out, const CompareResult& result) {
  out.precision(17);
  out << "alpha,beta,default,status,max_drift_position,max_drift_velocity,steps,wall_s,"
         "error_u\n";
  for (const auto& p : result.baumgarte_study) {
    out << p.alpha << "," << p.beta << "," << (p.is_default ? 1 : 0) << ","
        << (p.ok ? "ok" : "failed") << ",";
    if (p.ok) {
      out << p.max_drift_position << "," << p.max_drift_velocity << "," << p.steps << "," << p.wall
          << ",";
      if (std::isfinite(p.error_u)) out << p.error_u;
    } else {
      out << ",,,,";
    }
    out << "\n";
  }
}

/// Removes from the folder `base` what an earlier comparison left there and this one did not
/// write: the folder describes this comparison only.
void remove_stale_files(OutputPlan& plan, const std::filesystem::path& base,
                        const CompareResult& result) {
  // A study an earlier run left there would be drawn beside runs it does not belong to.
  if (!result.options.baumgarte_study) plan.remove_stale(base / "baumgarte_study.csv");
  // Figures are drawn after this from these files (validation/plot_compare.py), or not at all
  // (--no-plots): one an earlier comparison drew would show its schemes and tolerances.
  for (const char* figure :
       {"work_precision", "error_steps", "drift", "multipliers", "baumgarte_study"}) {
    for (const char* ext : {".png", ".pdf"}) plan.remove_stale(base / (std::string(figure) + ext));
  }
  // And the plotting script's log of those figures (rewritten when figures are drawn).
  plan.remove_stale(base / "plots.log");
  if (result.reference_t.empty()) plan.remove_stale(base / "history_reference.csv");
  // Nor a scheme's drift and history files that this comparison did not write (a scheme not
  // asked for, not applicable, or whose run left nothing).
  for (Scheme s : kSchemes) {
    const bool written = std::any_of(
        result.histories.begin(), result.histories.end(),
        [s](const auto& h) { return h.scheme == s && (h.ok || !h.trajectory.t.empty()); });
    if (written) continue;
    plan.remove_stale(base / drift_file(s));
    plan.remove_stale(base / history_file(s));
  }
}

}  // namespace

void write_compare_files(OutputPlan& plan, const std::string& dir, const CompareResult& result) {
  namespace fs = std::filesystem;
  plan_compare_files(plan, dir, result.options.schemes, result.options.baumgarte_study);
  plan.check();
  plan.create_folders();
  const fs::path base(dir);
  const auto put = [&](const std::string& path, OutputPlan::Writer writer) {
    plan.write(plan.add_output(path, kOutDir), std::move(writer));
  };

  std::vector<ReportFields> rows;
  for (const auto& r : result.runs) rows.push_back(fields(r));
  put((base / "runs.csv").string(),
      [&](std::ostream& out) { write_csv_table(out, fields(RunRecord{}), rows); });
  put((base / "runs.json").string(),
      [&](std::ostream& out) { write_runs_json(out, result, rows); });
  // A failed run's files hold its rows and steps before the failure (runs.json "histories").
  for (const auto& h : result.histories) {
    if (!h.ok && h.trajectory.t.empty()) continue;
    put((base / drift_file(h.scheme)).string(),
        [&](std::ostream& out) { write_drift_csv(out, h); });
    put((base / history_file(h.scheme)).string(),
        [&](std::ostream& out) { write_history_csv(out, result, h); });
  }
  if (!result.reference_t.empty()) {
    put((base / "history_reference.csv").string(),
        [&](std::ostream& out) { write_reference_history_csv(out, result); });
  }
  if (result.options.baumgarte_study) {
    put((base / "baumgarte_study.csv").string(),
        [&](std::ostream& out) { write_baumgarte_csv(out, result); });
  }
  put((base / "summary.txt").string(),
      [&](std::ostream& out) { print_compare_table(out, result); });
  plan.commit_all();
  remove_stale_files(plan, base, result);
}

std::string draw_compare_plots(const std::string& dir) {
  return run_plot_script("plot_compare.py", dir);
}

}  // namespace condyn
