#pragma once
/// Writes a StressResult: the terminal report, and the files of validation/stress-output.md.

#include <ostream>
#include <string>

#include "src/output/output_files.hpp"
#include "validation/studies/stress.hpp"

namespace condyn {

/// Per family: what it probes and what to expect, then one row per (case, scheme) with the
/// verdict; breaks are explained below each table; a closing map of verdicts per family and
/// scheme.
void print_stress_report(std::ostream& out, const StressResult& result);

/// Adds to `plan` the folder `dir` and the files stress writes there for `cases`, so that
/// plan.check() refuses a bad --out-dir before the runs.
void plan_stress_files(OutputPlan& plan, const std::string& dir,
                       const std::vector<StressCase>& cases);

/// Writes stress.csv, stress.json, summary.txt and scenes/<case>.toml (each case's scene, so a
/// run can be repeated with `condyn run`) into `dir`, all committed together through `plan`.
/// Throws OutputError (a path refused) or std::runtime_error naming the file.
void write_stress_files(OutputPlan& plan, const std::string& dir, const StressResult& result);
/// The same with a plan of its own.
void write_stress_files(const std::string& dir, const StressResult& result);

}  // namespace condyn
