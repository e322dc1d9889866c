#pragma once
/// `condyn plot RESULT`: figures of one run's result file (the CSV or HDF5 `condyn run` writes),
/// or of the mode shapes `condyn modes --shapes` writes, drawn by validation/plot_result.py with
/// Debian's matplotlib (docs/plots.md).

#include <string>

namespace condyn {

struct PlotArgs {
  std::string result;   ///< the run's .csv or .h5
  std::string out_dir;  ///< where the figures go (default: beside the result)
  std::string dofs;     ///< comma-separated DOF names or globs (default: the largest peaks)
  std::string columns;  ///< comma-separated columns for their own panels (default: the derived)
  std::string scene;    ///< the result's scene: its nodes, for the deformed or mode shapes
  std::string formats = "png,pdf";
};

/// Checks the arguments, runs the script and returns the exit code: 0 drawn; 2 bad input (a
/// missing file, not a result, an unknown DOF: the message names it); 1 the plotting tools are
/// missing or the script failed.
[[nodiscard]] int plot_result(const PlotArgs& args);

}  // namespace condyn
