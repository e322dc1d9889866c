#include "src/reports/stress_output.hpp"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>
#include <vector>

#include "src/reports/report_format.hpp"

namespace condyn {

namespace {

std::string sci(const std::optional<double>& v) {
  if (!v) return "-";
  std::ostringstream s;
  s << std::scientific << std::setprecision(1) << *v;
  return s.str();
}

/// One letter per verdict for the closing map.
char verdict_mark(const std::string& status) {
  if (status == "holds") return '+';
  if (status == "inaccurate") return '~';
  if (status == "failed") return 'x';
  return '.';  // refused
}

/// Fields of a record in the column order of stress.csv.
ReportFields fields(const StressRecord& r) {
  const auto opt = [](const std::optional<double>& v) {
    return v ? full_precision(*v) : std::string();
  };
  const bool ran = r.status == "holds" || r.status == "inaccurate";
  const auto if_ran = [&](double v) { return ran ? full_precision(v) : std::string(); };
  return {{"family", r.family},
          {"case", r.case_id},
          {"label", r.label},
          {"parameter", full_precision(r.parameter)},
          {"scheme", to_string(r.scheme)},
          {"status", r.status},
          {"rtol", full_precision(r.rtol)},
          {"reference", r.reference},
          {"error_u", opt(r.error)},
          {"max_drift_position", if_ran(r.max_drift_position)},
          {"max_drift_velocity", if_ran(r.max_drift_velocity)},
          {"energy_error", opt(r.energy_error)},
          {"steps", ran ? std::to_string(r.steps) : std::string()},
          {"wall_s", full_precision(r.wall_seconds)},
          {"t_reached", r.status == "refused" ? std::string() : full_precision(r.t_reached)},
          {"reason", r.reason},
          {"suggestion", r.suggestion}};
}

}  // namespace

void print_stress_report(std::ostream& out, const StressResult& result) {
  out << "condyn stress: " << result.cases.size() << " generated scenes, " << result.records.size()
      << " runs in " << std::fixed << std::setprecision(1) << result.wall_seconds << " s"
      << std::defaultfloat << "\n"
      << "verdicts: holds (error within " << kStressErrorFactor
      << " x rtol of the reference, or no reference), inaccurate (finished beyond that), failed "
         "(the integrator gave up), refused (the scene or the scheme said no, with the reason)\n";
  for (const auto& family : stress_families()) {
    bool any = false;
    for (const auto& r : result.records) any = any || r.family == family.name;
    if (!any) continue;
    out << "\n== " << family.name << ": " << family.question
        << "\n   expected: " << family.expectation << "\n";
    TextTable table({"case", "scheme", "verdict", "error u", "drift", "energy", "steps", "time s"},
                    "  ");
    std::ostringstream breaks;
    for (const auto& r : result.records) {
      if (r.family != family.name) continue;
      const bool ran = r.status == "holds" || r.status == "inaccurate";
      std::ostringstream wall;
      wall << std::fixed << std::setprecision(3) << r.wall_seconds;
      table.add_row({r.label, to_string(r.scheme), r.status, sci(r.error),
                     ran ? sci(r.max_drift_position) : "-", sci(r.energy_error),
                     ran ? std::to_string(r.steps) : "-", wall.str()});
      if (r.status == "failed" || r.status == "inaccurate") {
        breaks << "    " << r.label << ", " << to_string(r.scheme) << ": " << r.reason;
        if (r.status == "failed") breaks << " (reached t = " << r.t_reached << ")";
        if (!r.suggestion.empty()) breaks << "; suggestion: " << r.suggestion;
        breaks << "\n";
      }
    }
    table.print(out);
    if (!breaks.str().empty()) out << "  breaks:\n" << breaks.str();
    // Refusals repeat one reason per scheme: list each reason once.
    std::map<std::string, std::string> refusals;
    for (const auto& r : result.records) {
      if (r.family == family.name && r.status == "refused") {
        auto& who = refusals[r.reason];
        who += (who.empty() ? "" : ", ") + r.label + " " + to_string(r.scheme);
      }
    }
    if (!refusals.empty()) {
      out << "  refused:\n";
      for (const auto& [reason, who] : refusals) out << "    " << who << ": " << reason << "\n";
    }
  }
  // The map: one row per case, one column per scheme.
  out << "\nmap (+ holds, ~ inaccurate, x failed, . refused, blank: not part of the family):\n";
  std::vector<std::string> header = {""};
  for (Scheme s : kSchemes) header.emplace_back(to_string(s));
  TextTable map(header, "  ");
  for (const auto& c : result.cases) {
    std::vector<std::string> row = {c.family + " " + c.label};
    for (Scheme s : kSchemes) {
      char mark = ' ';
      for (const auto& r : result.records) {
        if (r.case_id == c.id && r.scheme == s) mark = verdict_mark(r.status);
      }
      row.emplace_back(1, mark);
    }
    map.add_row(std::move(row));
  }
  map.print(out);
}

namespace {
const char* const kStressOutDir = "--out-dir";
}  // namespace

void plan_stress_files(OutputPlan& plan, const std::string& dir,
                       const std::vector<StressCase>& cases) {
  namespace fs = std::filesystem;
  const fs::path base(dir);
  plan.add_folder(dir, kStressOutDir);
  plan.add_folder((base / "scenes").string(), kStressOutDir);
  for (const char* name : {"stress.csv", "stress.json", "summary.txt"}) {
    (void)plan.add_output((base / name).string(), kStressOutDir);
  }
  for (const auto& c : cases) {
    (void)plan.add_output((base / "scenes" / (c.id + ".toml")).string(), kStressOutDir);
  }
}

void write_stress_files(const std::string& dir, const StressResult& result) {
  OutputPlan plan;
  write_stress_files(plan, dir, result);
}

void write_stress_files(OutputPlan& plan, const std::string& dir, const StressResult& result) {
  namespace fs = std::filesystem;
  plan_stress_files(plan, dir, result.cases);
  plan.check();
  plan.create_folders();
  const fs::path base(dir);
  const auto put = [&](const std::string& path, OutputPlan::Writer writer) {
    plan.write(plan.add_output(path, kStressOutDir), std::move(writer));
  };
  std::vector<ReportFields> rows;
  for (const auto& r : result.records) rows.push_back(fields(r));
  put((base / "stress.csv").string(),
      [&](std::ostream& out) { write_csv_table(out, fields(StressRecord{}), rows); });
  put((base / "stress.json").string(), [&](std::ostream& out) {
    out << "{\n  \"wall_s\": " << full_precision(result.wall_seconds)
        << ",\n  \"error_factor\": " << full_precision(kStressErrorFactor)
        << ",\n  \"families\": [\n";
    const auto& families = stress_families();
    for (std::size_t k = 0; k < families.size(); ++k) {
      out << "    {\"name\": " << json_string(families[k].name)
          << ", \"question\": " << json_string(families[k].question)
          << ", \"expectation\": " << json_string(families[k].expectation) << "}"
          << (k + 1 < families.size() ? "," : "") << "\n";
    }
    out << "  ],\n  \"runs\": [\n";
    write_json_records(
        out, rows,
        {"family", "case", "label", "scheme", "status", "reference", "reason", "suggestion"},
        "    ");
    out << "  ]\n}\n";
  });
  for (std::size_t i = 0; i < result.cases.size(); ++i) {
    const auto& c = result.cases[i];
    put((base / "scenes" / (c.id + ".toml")).string(),
        [&](std::ostream& out) { out << c.scene_text; });
  }
  put((base / "summary.txt").string(),
      [&](std::ostream& out) { print_stress_report(out, result); });
  plan.commit_all();
  // The folder describes this run only: a generated scene an earlier run of other families left
  // in scenes/ (FAMILY_K.toml) goes, the user's other files stay.
  std::vector<std::filesystem::path> stale;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(base / "scenes", ec)) {
    const std::string stem = entry.path().stem().string();
    const bool generated =
        entry.path().extension() == ".toml" &&
        std::any_of(stress_families().begin(), stress_families().end(),
                    [&](const auto& f) { return stem.rfind(f.name + "_", 0) == 0; });
    const bool current = std::any_of(result.cases.begin(), result.cases.end(),
                                     [&](const auto& c) { return c.id == stem; });
    if (generated && !current) stale.push_back(entry.path());
  }
  for (const auto& path : stale) plan.remove_stale(path);
}

}  // namespace condyn
