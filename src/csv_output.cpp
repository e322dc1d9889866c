#include "src/csv_output.hpp"

#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace condyn {

namespace {

void write_rows(std::ostream& out, const Model& model, const Trajectory& traj) {
  out.precision(17);
  out << "t";
  const auto& q = model.output.quantities;
  for (Quantity quantity : q) {
    switch (quantity) {
      case Quantity::displacement:
        for (const auto& d : model.dof_names) out << "," << d;
        break;
      case Quantity::velocity:
        for (const auto& d : model.dof_names) out << ",vel_" << d;
        break;
      case Quantity::reaction:
        for (const auto& d : model.dof_names) out << ",reaction_" << d;
        break;
      case Quantity::multiplier:
        for (const auto& c : model.constraints) out << ",lambda_" << c.name;
        break;
      case Quantity::drift:
        out << ",drift_position,drift_velocity";
        break;
      case Quantity::energy:
        out << ",energy,energy_error";
        break;
    }
  }
  out << "\n";
  for (std::size_t k = 0; k < traj.t.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    out << traj.t[k];
    auto column = [&](const Eigen::MatrixXd& m) {
      for (Eigen::Index i = 0; i < m.rows(); ++i) out << "," << m(i, col);
    };
    for (Quantity quantity : q) {
      switch (quantity) {
        case Quantity::displacement:
          column(traj.u);
          break;
        case Quantity::velocity:
          column(traj.v);
          break;
        case Quantity::reaction:
          column(traj.reaction);
          break;
        case Quantity::multiplier:
          column(traj.multiplier);
          break;
        case Quantity::drift:
          out << "," << traj.drift_position[col] << "," << traj.drift_velocity[col];
          break;
        case Quantity::energy:  // build_model refuses 'energy' for nonconservative scenes
          out << "," << traj.energy[col] << "," << traj.energy[col] - traj.energy[0];
          break;
      }
    }
    out << "\n";
  }
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& writer) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path target(path);
  // A symbolic link keeps pointing where it did: the file it names is replaced, not the link.
  if (fs::is_symlink(fs::symlink_status(target, ec))) {
    const fs::path resolved = fs::weakly_canonical(target, ec);
    if (!ec) target = resolved;
  }
  const fs::file_status status = fs::status(target, ec);
  if (fs::is_directory(status)) throw std::runtime_error(path + ": is a directory");
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error(path + ": " + what + " (" + std::strerror(errno) + ")");
  };
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    // A device, FIFO or socket (/dev/null, /dev/stdout, a pipe): renaming over it would replace
    // the special file with a regular one, so the output is streamed into it instead.
    std::ofstream out(target, std::ios::binary);
    if (!out) fail("cannot write output");
    writer(out);
    out.flush();
    if (!out) fail("writing the output failed");
    return;
  }
  const fs::path tmp =
      target.parent_path() / ("." + target.filename().string() + ".tmp" + std::to_string(getpid()));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail("cannot write output");
    writer(out);
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw std::runtime_error(path + ": writing the output failed");
    }
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw std::runtime_error(path + ": cannot move the output into place (" + ec.message() + ")");
  }
}

void write_csv_atomically(const std::string& path, const Model& model, const Trajectory& traj) {
  write_file_atomically(path, [&](std::ostream& out) { write_rows(out, model, traj); });
}

void write_steps_csv_atomically(const std::string& path, const Trajectory& traj) {
  write_file_atomically(path, [&](std::ostream& out) {
    out.precision(17);
    out << "t,drift_position,drift_velocity\n";
    for (const auto& s : traj.steps) {
      out << s.t << "," << s.drift_position << "," << s.drift_velocity << "\n";
    }
  });
}

}  // namespace condyn
