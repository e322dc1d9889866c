#pragma once
/// Writes a CompareResult: the terminal table, and the files of validation/compare-output.md.

#include <ostream>
#include <string>

#include "src/output/output_files.hpp"
#include "validation/studies/compare.hpp"

namespace condyn {

/// The work-precision table, one row per run.
void print_compare_table(std::ostream& out, const CompareResult& result);

/// Adds to `plan` the folder `dir` and the files compare writes there for `schemes` (and
/// baumgarte_study.csv when the study runs), so that plan.check() refuses a bad --out-dir before
/// the runs.
void plan_compare_files(OutputPlan& plan, const std::string& dir,
                        const std::vector<Scheme>& schemes, bool baumgarte_study);

/// Writes runs.csv, runs.json, drift_<scheme>.csv, history_<scheme>.csv, baumgarte_study.csv and
/// summary.txt into `dir` (created if missing), all committed together through `plan`. Throws
/// OutputError (a path refused) or std::runtime_error naming the file.
void write_compare_files(OutputPlan& plan, const std::string& dir, const CompareResult& result);
/// The same with a plan of its own.
void write_compare_files(const std::string& dir, const CompareResult& result);

/// Runs validation/plot_compare.py on `dir` with Debian's python3. Returns a one-line note: what
/// was drawn, or why plots were skipped (no python3, no matplotlib, no script).
[[nodiscard]] std::string draw_compare_plots(const std::string& dir);

}  // namespace condyn
