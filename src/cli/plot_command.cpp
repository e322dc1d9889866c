#include "src/cli/plot_command.hpp"

#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "src/cli/cli_flags.hpp"
#include "src/cli/commands.hpp"
#include "src/output/output_files.hpp"
#include "src/output/output_format.hpp"
#include "src/reports/report_format.hpp"

namespace condyn {

namespace {

int bad(const std::string& message) {
  std::cerr << "error: " << message << "\n";
  return 2;
}

}  // namespace

int plot_result(const PlotArgs& args) {
  namespace fs = std::filesystem;
  const fs::path result(args.result);
  std::error_code ec;
  if (fs::is_directory(result, ec)) {
    return bad(args.result + ": is a folder (condyn plot reads the CSV or HDF5 of condyn run)");
  }
  if (!fs::exists(result, ec)) {
    return bad(args.result + ": no such file (condyn plot reads the CSV or HDF5 of condyn run)");
  }
  if (!fs::is_regular_file(result, ec)) {  // a FIFO or a device: reading it could block
    return bad(args.result +
               ": not a regular file (condyn plot reads the CSV or HDF5 of condyn run)");
  }
  // The names run writes results under (src/output/output_format.hpp): CSV or HDF5 by extension.
  if (!has_no_extension(args.result) && named_format(args.result) != FileFormat::csv &&
      named_format(args.result) != FileFormat::hdf5) {
    return bad(args.result + ": not a result file: condyn plot reads what condyn run writes, " +
               accepted_names({FileFormat::csv, FileFormat::hdf5}));
  }
  // The list rules of the other lists: no empty item, none twice, blanks ignored.
  const std::vector<std::string> format_list = split_list("--format", args.formats);
  std::string formats;
  for (const auto& format : format_list) {
    if (format != "png" && format != "pdf" && format != "svg") {
      return bad("--format: unknown format '" + format + "' (png, pdf, svg)");
    }
    formats += (formats.empty() ? "" : ",") + format;
  }
  const fs::path out_dir = args.out_dir.empty() ? result.parent_path() : fs::path(args.out_dir);
  // A folder made here goes again when nothing is drawn into it (a --dofs that matches none).
  fs::path created;
  if (!out_dir.empty()) {
    if (!fs::exists(out_dir, ec)) {
      fs::path top = out_dir;  // the outermost folder that does not exist yet
      while (top.has_parent_path() && !top.parent_path().empty() &&
             !fs::exists(top.parent_path(), ec)) {
        top = top.parent_path();
      }
      created = top;
    }
    fs::create_directories(out_dir, ec);
    if (!fs::is_directory(out_dir)) {
      return bad("--out-dir " + out_dir.string() + ": cannot create the folder");
    }
  }
  const auto remove_created = [&] {
    if (created.empty()) return;
    for (fs::path p = out_dir;; p = p.parent_path()) {  // empty folders only, inner first
      fs::remove(p, ec);
      if (p == created || !p.has_parent_path()) break;
    }
  };
  // Every figure the script may write is checked as run checks its files, before any is drawn:
  // a folder in the way, a file without write permission (protected), a folder that takes no
  // new file, the result itself. The script then writes them (the plan's temporaries go).
  try {
    OutputPlan plan;
    plan.add_input(args.result);
    const std::string stem = result.stem().string();
    for (const char* kind : {"displacement", "columns", "drift", "energy"}) {
      for (const auto& f : format_list) {
        (void)plan.add_output((out_dir / (stem + "_" + kind + "." + f)).string(), "the figure");
      }
    }
    plan.check();
  } catch (const OutputError& e) {
    remove_created();
    return bad(e.what());
  }
  const fs::path script = validation_script("plot_result.py");
  if (!fs::exists(script)) {
    std::cerr << "error: " << script.string() << " not found: the plots need the source tree\n";
    return 1;
  }
  std::vector<std::string> script_args = {
      args.result, "--out-dir", out_dir.empty() ? "." : out_dir.string(), "--format", formats};
  if (!args.dofs.empty()) script_args.insert(script_args.end(), {"--dofs", args.dofs});
  if (!args.columns.empty()) script_args.insert(script_args.end(), {"--columns", args.columns});
  const int code = run_python_script(script, script_args, "");
  if (code != 0) remove_created();
  switch (code) {
    case 0:
      return 0;
    case 2:
      return 2;  // bad input: the script named the file and what is wrong
    case 3:
      std::cerr << "error: plots need Debian's python3-matplotlib, python3-numpy and (for .h5) "
                   "python3-h5py: apt-get install them\n";
      return 1;
    case 127:
      std::cerr << "error: python3 is not installed (apt-get install python3-matplotlib)\n";
      return 1;
    default:
      std::cerr << "error: the plotting script failed (exit " << code << ")\n";
      return 1;
  }
}

Command add_plot_command(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  auto* cmd = app.add_subcommand(
      "plot",
      "figures of one run's CSV or HDF5: displacements, derived columns, drift, energy "
      "(docs/plots.md)");
  cmd->add_option("result", args->result, "the CSV or HDF5 file that condyn run wrote")->required();
  cmd->add_option("--dofs", args->dofs,
                  "DOFs to draw, names or globs, comma-separated (default: the four with the "
                  "largest peaks)")
      ->check(non_empty_check());
  cmd->add_option("--columns", args->columns,
                  "columns to draw one panel each, names or globs, comma-separated (default: "
                  "the result's [[derived]] columns)")
      ->check(non_empty_check());
  cmd->add_option("--out-dir", args->out_dir, "folder for the figures (default: beside RESULT)")
      ->check(non_empty_check());
  cmd->add_option("--format", args->formats, "comma-separated: png, pdf, svg (default: png,pdf)")
      ->check(non_empty_check());
  return {cmd, [args] { return plot_result(*args); }};
}

}  // namespace condyn
