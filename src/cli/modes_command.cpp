// condyn modes: the constrained model's natural modes, lowest first, as CSV or as one HDF5 file
// with the shapes (docs/cli.md).

#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "models/scene/scene_parser.hpp"
#include "src/cli/cli_flags.hpp"
#include "src/cli/commands.hpp"
#include "src/output/csv_rows.hpp"
#include "src/output/hdf5_modes.hpp"
#include "src/output/output_files.hpp"
#include "src/output/output_format.hpp"
#include "validation/studies/scene_modes.hpp"

namespace condyn {

namespace {

struct ModesArgs {
  std::string scene, out, shapes;
  std::optional<int> count;
};

/// `mode, omega, frequency, period` and, under [ground_motion], `mass_ratio,
/// mass_ratio_cumulative`: one row a mode. A zero-frequency mode's period is `inf`.
void write_table(std::ostream& out, const SceneModes& s) {
  const NaturalModes& m = s.modes;
  out << "mode,omega,frequency,period"
      << (s.ground_motion ? ",mass_ratio,mass_ratio_cumulative" : "") << "\n";
  std::string line;
  for (Eigen::Index j = 0; j < m.omega.size(); ++j) {
    line = std::to_string(j + 1);
    const double omega = m.omega[j];
    for (const double v : {omega, mode_frequency(omega), mode_period(omega)}) {
      line += ',';
      append_number(line, v);
    }
    if (s.ground_motion) {
      for (const double v : {m.mass_ratio[j], m.mass_ratio_cumulative[j]}) {
        line += ',';
        append_number(line, v);
      }
    }
    out << line << "\n";
  }
}

/// `dof, mode_1, ..., mode_K`: one row a DOF, each shape mass-normalized (φᵀMφ = 1).
void write_shapes(std::ostream& out, const SceneModes& s) {
  const Eigen::MatrixXd& phi = s.modes.shapes;
  out << "dof";
  for (Eigen::Index j = 0; j < phi.cols(); ++j) out << ",mode_" << j + 1;
  out << "\n";
  std::string line;
  for (Eigen::Index i = 0; i < phi.rows(); ++i) {
    line = s.dof_names[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < phi.cols(); ++j) {
      line += ',';
      append_number(line, phi(i, j));
    }
    out << line << "\n";
  }
}

int modes(const ModesArgs& args) {
  const SceneSpec spec = parse_scene_file(args.scene);
  OutputPlan plan;  // every output checked before the eigensolve, committed together after it
  plan.add_input(args.scene);
  for (const auto& input : spec.input_files) plan.add_input(input);
  const std::string table_path = args.out.empty() ? "-" : args.out;
  const auto table = plan.add_output(table_path, "--out");
  std::optional<OutputPlan::Id> shapes;
  if (!args.shapes.empty()) shapes = plan.add_output(args.shapes, "--shapes");
  plan.check();
  // HDF5 holds the table and the shapes in one file (src/output/hdf5_modes.hpp).
  const bool hdf5 =
      output_format(table_path, "--out", {FileFormat::csv, FileFormat::hdf5}) == FileFormat::hdf5;
  if (shapes) (void)output_format(args.shapes, "--shapes", {FileFormat::csv});
  const SceneModes s = scene_modes(spec, args.count, "--count");
  plan.write(table, [&s, hdf5](std::ostream& out) {
    if (hdf5) {
      write_modes_hdf5(out, s);
    } else {
      write_table(out, s);
    }
  });
  if (shapes) plan.write(*shapes, [&s](std::ostream& out) { write_shapes(out, s); });
  plan.commit_all();
  // What else is said goes to standard error when a CSV is on standard output.
  std::ostream& msg = plan.any_to_stdout() ? std::cerr : std::cout;
  msg << s.modes.omega.size() << " of " << s.modes.available << " modes ("
      << (s.modes.dense ? "dense eigensolver" : "shift-invert Lanczos") << ")";
  if (s.ground_motion) msg << ", total mass along the influence vector " << s.modes.total_mass;
  msg << "\n";
  if (!args.out.empty()) {
    msg << "wrote the modes" << (hdf5 ? " and their shapes" : "") << " to "
        << plan.display_name(table) << "\n";
  }
  if (shapes) msg << "wrote the mode shapes to " << plan.display_name(*shapes) << "\n";
  return 0;
}

}  // namespace

Command add_modes_command(CLI::App& app) {
  auto args = std::make_shared<ModesArgs>();
  auto* cmd = app.add_subcommand("modes",
                                 "natural modes of the constrained model at t = 0, lowest first "
                                 "(CSV, or HDF5 with the shapes)");
  cmd->add_option("scene", args->scene, "scene file (TOML)")->required();
  cmd->add_option("--count", args->count,
                  "how many modes (default " + std::to_string(kDefaultModeCount) +
                      ", or all when the model has fewer)")
      ->check(whole_check(1, std::numeric_limits<int>::max()));
  cmd->add_option("--out", args->out,
                  "write the table to this CSV file (default: standard output), or the table and "
                  "the mode shapes to this HDF5 file (.h5, .hdf5, .hdf)")
      ->check(file_name_check());
  cmd->add_option("--shapes", args->shapes,
                  "also write the mode shapes (one row a DOF, one column a mode) to this CSV file")
      ->check(file_name_check());
  return {cmd, [args] { return modes(*args); }, [args] { return args->scene; }};
}

}  // namespace condyn
