#include "src/cli/plot_command.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/number_cell.hpp"
#include "models/scene/scene_node_map.hpp"
#include "models/scene/scene_parser.hpp"
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

/// The scene's node map for validation/plot_shapes.py: {"dimension", "nodes", "position",
/// "dofs", "edges"}, every number finite (checked by the scene reader).
void write_node_map(const NodeMap& map, const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary);
  const auto list = [&](std::size_t n, const auto& item) {
    out << "[";
    for (std::size_t k = 0; k < n; ++k) {
      out << (k ? "," : "");
      item(k);
    }
    out << "]";
  };
  out << "{\"dimension\":" << map.dimension << ",\"nodes\":";
  list(map.nodes.size(), [&](std::size_t k) { out << json_string(map.nodes[k]); });
  out << ",\"position\":";
  list(map.position.size(), [&](std::size_t k) {
    list(3, [&](std::size_t a) { out << shortest_number(map.position[k][a]); });
  });
  out << ",\"dofs\":";
  list(map.dofs.size(),
       [&](std::size_t k) { list(3, [&](std::size_t a) { out << json_string(map.dofs[k][a]); }); });
  out << ",\"edges\":";
  list(map.edges.size(),
       [&](std::size_t k) { out << "[" << map.edges[k][0] << "," << map.edges[k][1] << "]"; });
  out << "}\n";
  if (!out) throw OutputError(path.string() + ": cannot write the node map for the plot");
}

/// Runs validation/plot_result.py with `args`, and the node map (when not empty) in a temporary
/// file of its own, removed after it: the script's exit code.
int run_plot(const std::filesystem::path& script, std::vector<std::string> args,
             const NodeMap& nodes) {
  namespace fs = std::filesystem;
  const fs::path map_file =
      fs::temp_directory_path() / ("condyn-plot-nodes-" + std::to_string(::getpid()) + ".json");
  if (!nodes.empty()) {
    write_node_map(nodes, map_file);
    args.insert(args.end(), {"--nodes", map_file.string()});
  }
  const int code = run_python_script(script, args, "");
  std::error_code ec;
  if (!nodes.empty()) fs::remove(map_file, ec);
  return code;
}

/// The command's exit code for the script's: 0 drawn, 2 bad input (the script named it), else 1
/// with what is missing or failed.
int plot_exit(int code) {
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
  // The nodes the shapes are drawn on, from the scene (refused there when it is bad).
  NodeMap nodes;
  if (!args.scene.empty()) {
    nodes = scene_node_map(parse_scene_file(args.scene));
    if (nodes.empty()) {
      return bad("--scene " + args.scene +
                 ": no nodes to draw shapes on: a truss has its nodes, a matrix model needs "
                 "[model] coordinates (docs/scenes.md), other models have none");
    }
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
    for (const char* kind : {"displacement", "columns", "drift", "energy", "shape", "modes"}) {
      if (nodes.empty() && (kind == std::string_view("shape") || kind == std::string_view("modes")))
        continue;
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
  int code = 0;
  try {
    code = run_plot(script, script_args, nodes);
  } catch (const OutputError& e) {
    remove_created();
    return bad(e.what());
  }
  if (code != 0) remove_created();
  return plot_exit(code);
}

Command add_plot_command(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  auto* cmd = app.add_subcommand(
      "plot",
      "figures of one run's CSV or HDF5: displacements, derived columns, drift, energy, and with "
      "--scene the deformed shape (or the mode shapes of condyn modes --shapes, or of condyn "
      "modes --out FILE.h5 with each mode's frequency and period) (docs/plots.md)");
  cmd->add_option("result", args->result, "the CSV or HDF5 file that condyn run wrote")->required();
  cmd->add_option("--dofs", args->dofs,
                  "DOFs to draw, names or globs, comma-separated (default: the four with the "
                  "largest peaks)")
      ->check(non_empty_check());
  cmd->add_option("--columns", args->columns,
                  "columns to draw one panel each, names or globs, comma-separated (default: "
                  "the result's [[derived]] columns)")
      ->check(non_empty_check());
  cmd->add_option("--scene", args->scene,
                  "the scene of the result: its nodes (a truss's, a matrix model's [model] "
                  "coordinates) for the deformed shape, or the mode shapes of condyn modes "
                  "--shapes or --out FILE.h5")
      ->check(non_empty_check());
  cmd->add_option("--out-dir", args->out_dir, "folder for the figures (default: beside RESULT)")
      ->check(non_empty_check());
  cmd->add_option("--format", args->formats, "comma-separated: png, pdf, svg (default: png,pdf)")
      ->check(non_empty_check());
  return {cmd, [args] { return plot_result(*args); }};
}

}  // namespace condyn
