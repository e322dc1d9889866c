#include "src/csv_output.hpp"

#include <filesystem>
#include <iostream>
#include <sstream>

namespace condyn {

namespace {

void write_rows(std::ostream& out, const Model& model, const std::vector<Quantity>& q,
                const Trajectory& traj) {
  out.precision(17);
  out << "t";
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

/// FILE.csv -> FILE.partial.csv (beside it): where a failed run keeps what it computed, so that
/// the file the user named is never overwritten by an incomplete result.
std::string partial_path(const std::string& out) {
  const std::filesystem::path p(out);
  return (p.parent_path() / (p.stem().string() + ".partial" + p.extension().string())).string();
}

}  // namespace

void write_steps_csv(std::ostream& out, const Trajectory& traj) {
  out.precision(17);
  out << "t,drift_position,drift_velocity\n";
  for (const auto& s : traj.steps) {
    out << s.t << "," << s.drift_position << "," << s.drift_velocity << "\n";
  }
}

RunOutputs::RunOutputs(const std::string& scene, const std::string& out_flag,
                       const OutputSpec& output, const std::string& steps_out)
    : quantities_(output.quantities) {
  const std::string& output_file = output.file;
  plan_.add_input(scene);
  if (!out_flag.empty()) {
    csv_ = plan_.add_output(out_flag, "--out");
  } else if (!output_file.empty()) {
    csv_ = plan_.add_output(output_file, scene + ": [output] file");
  } else {
    const std::string name = std::filesystem::path(scene).stem().string() + ".csv";
    csv_ = plan_.add_output(name, "the default output (SCENE-STEM.csv)");
  }
  if (!steps_out.empty()) steps_ = plan_.add_output(steps_out, "--steps-out");
  plan_.check();  // the stream test below needs the CSV resolved
  if (!plan_.is_stream(csv_)) {
    partial_ = plan_.add_output(partial_path(plan_.display_name(csv_)), "the partial-result file");
    plan_.check();
  }
}

std::ostream& RunOutputs::messages() const { return plan_.any_to_stdout() ? std::cerr : std::cout; }

std::string RunOutputs::csv_name() const { return plan_.display_name(csv_); }

std::string RunOutputs::steps_name() const { return steps_ ? plan_.display_name(*steps_) : ""; }

void RunOutputs::write(const Model& model, const Trajectory& traj) {
  plan_.write(csv_, [&](std::ostream& out) { write_rows(out, model, quantities_, traj); });
  std::vector<OutputPlan::Id> ids{csv_};
  if (steps_) {
    plan_.write(*steps_, [&](std::ostream& out) { write_steps_csv(out, traj); });
    ids.push_back(*steps_);
  }
  plan_.commit(ids);
}

std::string RunOutputs::write_partial(const Model& model, const Trajectory& partial) {
  std::ostringstream s;
  s << "partial result: the " << partial.t.size() << " output rows up to t = " << partial.t.back();
  if (!partial_) {
    s << " were not written (" << csv_name()
      << " is not a file: a stream, such as standard output, a device or a pipe, gets complete "
         "results only; give --out FILE to keep them)";
    return s.str();
  }
  try {
    plan_.write(*partial_,
                [&](std::ostream& out) { write_rows(out, model, quantities_, partial); });
    plan_.commit({*partial_});
    s << " are in " << plan_.display_name(*partial_) << " (the run did not reach t_end; "
      << csv_name() << " was not written)";
  } catch (const std::exception& e) {
    s << " could not be written: " << e.what();
  }
  return s.str();
}

}  // namespace condyn
