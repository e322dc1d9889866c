#pragma once
/// Writes a CompareResult: the terminal table, and the files of validation/compare-output.md.

#include <ostream>
#include <string>

#include "validation/compare.hpp"

namespace condyn {

/// The work-precision table, one row per run.
void print_compare_table(std::ostream& out, const CompareResult& result);

/// Writes runs.csv, runs.json, drift_<scheme>.csv, history_<scheme>.csv, baumgarte_study.csv and
/// summary.txt into `dir` (created if missing). Throws std::runtime_error naming the file.
void write_compare_files(const std::string& dir, const CompareResult& result);

/// Runs validation/plot_compare.py on `dir` with Debian's python3. Returns a one-line note: what
/// was drawn, or why plots were skipped (no python3, no matplotlib, no script).
[[nodiscard]] std::string draw_compare_plots(const std::string& dir);

}  // namespace condyn
