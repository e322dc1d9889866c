#include "src/output/csv_output.hpp"

#include "src/output/csv_rows.hpp"
#include "src/output/hdf5_output.hpp"
#include "src/output/output_format.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

namespace condyn {

namespace {

void write_rows(std::ostream& out, const Model& model, const OutputSpec& output,
                const Trajectory& whole) {
  const OutputColumns columns(model, output);
  out << csv_header(output, columns) << "\n";
  // A mechanism's rows in its output map's columns (a copy: the caller's trajectory stays).
  std::optional<Trajectory> mapped;
  if (columns.mapped())
    mapped = mapped_trajectory(
        model, whole, columns.points(),
        reads_reactions(with_derived_quantities(output.quantities, model.derived)));
  const Trajectory& traj = mapped ? *mapped : whole;
  const Eigen::VectorXd none;
  std::string line;
  const bool absolute = std::find(output.quantities.begin(), output.quantities.end(),
                                  Quantity::absolute_acceleration) != output.quantities.end();
  const auto column = [&none](const Eigen::MatrixXd& m, Eigen::Index col) {
    return m.cols() > col ? Eigen::Ref<const Eigen::VectorXd>(m.col(col))
                          : Eigen::Ref<const Eigen::VectorXd>(none);
  };
  for (std::size_t k = 0; k < traj.t.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    const Eigen::VectorXd absolute_acceleration =
        absolute ? model.absolute_acceleration(traj.t[k], traj.acceleration.col(col)) : none;
    const CsvRow row{traj.t[k],
                     traj.u.col(col),
                     traj.v.col(col),
                     column(traj.acceleration, col),
                     absolute_acceleration,
                     traj.reaction.col(col),
                     traj.multiplier.col(col),
                     traj.drift_position[col],
                     traj.drift_velocity[col],
                     traj.balance.size() > k ? &traj.balance[k] : nullptr,
                     column(traj.points, col),
                     traj.near_singular.size() > k && traj.near_singular[k]};
    line.clear();
    append_csv_row(line, output, columns, row);
    out << line << "\n";
  }
}

/// FNV-1a, 32 bits: a short, stable digest of a name.
std::uint32_t name_hash(const std::string& name) {
  std::uint32_t h = 2166136261U;
  for (const char c : name) {
    h ^= static_cast<unsigned char>(c);
    h *= 16777619U;
  }
  return h;
}

/// The longest name the folder of `path` takes (NAME_MAX, 255 bytes, on most file systems).
std::size_t name_limit(const std::filesystem::path& path) {
  const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  const long limit = ::pathconf(folder.c_str(), _PC_NAME_MAX);
  return limit > 0 ? static_cast<std::size_t>(limit) : static_cast<std::size_t>(NAME_MAX);
}

/// FILE.csv -> FILE.partial.csv (beside it): where a failed run keeps what it computed, so that
/// the file the user named is never overwritten by an incomplete result. A name that fits the
/// file system while its partial name would not (FILE of 248 bytes and more, as the limit is 255)
/// keeps the start of its stem, cut at a character, then `~` and 8 hex digits of a hash of the
/// whole name: `FILE-START~1a2b3c4d.partial.csv`, within the limit, and different for names
/// that share their start.
std::string partial_path(const std::string& out) {
  const std::filesystem::path p(out);
  const std::string stem = p.stem().string();
  const std::string tail = ".partial" + p.extension().string();
  const std::size_t limit = name_limit(p);
  if (stem.size() + tail.size() <= limit) return (p.parent_path() / (stem + tail)).string();
  char digest[16];
  std::snprintf(digest, sizeof digest, "~%08x",
                static_cast<unsigned>(name_hash(p.filename().string())));
  const std::size_t room = limit > tail.size() + 9 ? limit - tail.size() - 9 : 0;
  std::size_t cut = std::min(room, stem.size());
  while (cut > 0 && (static_cast<unsigned char>(stem[cut]) & 0xC0U) == 0x80U) --cut;  // UTF-8
  return (p.parent_path() / (stem.substr(0, cut) + digest + tail)).string();
}

/// "the output row at t = 0" or "the 12 output rows up to t = 0.11".
std::string rows_phrase(long rows, double t_last) {
  std::ostringstream s;
  if (rows == 1) {
    s << "the output row at t = " << t_last;
  } else {
    s << "the " << rows << " output rows up to t = " << t_last;
  }
  return s.str();
}

}  // namespace

std::string failure_message(const SolveResult& result, double t_end,
                            const std::string& partial_note) {
  return describe_failure(result, t_end) +
         (partial_note.empty() ? std::string() : "\n  " + partial_note);
}

void write_steps_csv(std::ostream& out, const Trajectory& traj) {
  out << "t,drift_position,drift_velocity\n";
  std::string line;
  for (const auto& s : traj.steps) {
    line.clear();
    append_number(line, s.t);
    line += ',';
    append_number(line, s.drift_position);
    line += ',';
    append_number(line, s.drift_velocity);
    out << line << "\n";
  }
}

RunOutputs::RunOutputs(const std::string& scene, const std::string& out_flag,
                       const OutputSpec& output, const std::string& steps_out,
                       const std::vector<std::string>& inputs, const std::string& out_source)
    : output_(output),
      ask_for_file_(out_source + (out_source.rfind("--", 0) == 0 ? " FILE" : "=FILE")) {
  const std::string& output_file = output.file;
  if (!scene.empty()) plan_.add_input(scene);
  for (const auto& in : inputs) plan_.add_input(in);
  std::string path, source;
  if (!out_flag.empty()) {
    path = out_flag;
    source = out_source;
  } else if (!output_file.empty()) {
    const std::filesystem::path file(output_file);
    path = file.is_absolute() ? output_file
                              : (std::filesystem::path(scene).parent_path() / file).string();
    source = scene + (output.file_line > 0 ? ":" + std::to_string(output.file_line) : "") +
             ": [output] file";
  } else {
    path = std::filesystem::path(scene).stem().string() + ".csv";
    source = "the default output (SCENE-STEM.csv)";
  }
  csv_ = plan_.add_output(path, source);
  if (!steps_out.empty()) steps_ = plan_.add_output(steps_out, "--steps-out");
  plan_.check();  // the stream test below needs the CSV resolved
  // The formats the names ask for, once the paths are known good (a name that is an input or a
  // folder says so first): the result CSV or HDF5, the drift log CSV only.
  format_ = output_format(path, source, {FileFormat::csv, FileFormat::hdf5});
  if (steps_) (void)output_format(steps_out, "--steps-out", {FileFormat::csv});
  if (!plan_.is_stream(csv_)) {
    partial_ = plan_.add_output(partial_path(plan_.display_name(csv_)), "the partial-result file");
  }
  if (steps_ && !plan_.is_stream(*steps_)) {
    steps_partial_ =
        plan_.add_output(partial_path(plan_.display_name(*steps_)), "the partial drift log");
  }
  plan_.check();
}

std::ostream& RunOutputs::messages() const { return plan_.any_to_stdout() ? std::cerr : std::cout; }

std::string RunOutputs::csv_name() const { return plan_.display_name(csv_); }

std::string RunOutputs::steps_name() const { return steps_ ? plan_.display_name(*steps_) : ""; }

void RunOutputs::write_result(OutputPlan::Id id, const Model& model, const RunAttributes& run,
                              const Trajectory& traj) {
  // A stream's writer runs later, at commit (OutputPlan): it captures what it needs by value or
  // refers to what outlives the commit (the model, the trajectory, the caller's attributes).
  const bool hdf5 = format_ == FileFormat::hdf5;
  plan_.write(id, [this, hdf5, &model, &run, &traj](std::ostream& out) {
    if (hdf5) {
      write_hdf5(out, model, output_, run, traj);
    } else {
      write_rows(out, model, output_, traj);
    }
  });
}

std::string RunOutputs::keep(const Model& model, const RunAttributes& run, const Trajectory& traj,
                             bool finished) {
  if (rows_) {  // streamed: the rows are in the result's temporary file
    if (!finished) return finish_stream_partial(run, traj);
    finish_stream(run, traj);
  } else {
    if (!finished) return traj.t.empty() ? "" : write_partial(model, run, traj);
    write(model, run, traj);
  }
  return "";
}

void RunOutputs::write(const Model& model, const RunAttributes& run, const Trajectory& traj) {
  write_result(csv_, model, run, traj);
  commit_result(traj);
}

void RunOutputs::commit_result(const Trajectory& traj) {
  std::vector<OutputPlan::Id> ids{csv_};
  if (steps_) {
    plan_.write(*steps_, [&](std::ostream& out) { write_steps_csv(out, traj); });
    ids.push_back(*steps_);
  }
  plan_.commit(ids);
  // The result is complete: a partial file an earlier failed run left under these names would
  // now look like a later, shorter result. Removed as outputs are protected (remove_stale).
  for (const auto& partial : {partial_, steps_partial_}) {
    if (partial && plan_.remove_stale(plan_.display_name(*partial))) {
      removed_.push_back(plan_.display_name(*partial));
    }
  }
}

std::function<void(const TrajectoryRow&)> RunOutputs::stream_rows(const Model& model) {
  rows_path_ = plan_.write_in_place(csv_);
  rows_ = open_row_writer(rows_path_, format_ == FileFormat::hdf5, model, output_);
  return [this](const TrajectoryRow& row) { rows_->row(row); };
}

void RunOutputs::finish_stream(const RunAttributes& run, const Trajectory& traj) {
  rows_->finish(run);
  commit_result(traj);
}

std::string RunOutputs::commit_partial(std::optional<OutputPlan::Id> rows,
                                       const Trajectory& partial) {
  std::vector<OutputPlan::Id> ids;
  if (rows) ids.push_back(*rows);
  std::string steps;
  if (steps_ && !partial.steps.empty()) {
    const std::string count = std::to_string(partial.steps.size());
    if (!steps_partial_) {
      steps = "; the drift at its " + count + " internal steps was not written (" + steps_name() +
              " is a stream)";
    } else {
      try {
        plan_.write(*steps_partial_,
                    [&partial](std::ostream& out) { write_steps_csv(out, partial); });
        ids.push_back(*steps_partial_);
        steps = "; the drift at its " + count + " internal steps is in " +
                plan_.display_name(*steps_partial_);
      } catch (const std::exception& e) {
        steps = "; the drift at its internal steps could not be written: " + std::string(e.what());
      }
    }
  }
  if (!ids.empty()) plan_.commit(ids);  // together: a commit removes the temporaries it leaves
  return steps;
}

std::string RunOutputs::finish_stream_partial(const RunAttributes& run, const Trajectory& partial) {
  // Every row computed is kept, the initial state alone too (a run that failed before its second
  // output time): a partial file left by an earlier failure would otherwise look current.
  if (!rows_ || rows_->rows() < 1) return "";
  std::ostringstream s;
  const bool one = rows_->rows() == 1;
  s << "partial result: " << rows_phrase(rows_->rows(), partial.t.back());
  try {
    rows_->finish(run);
    // The rows are complete in the result's temporary file: copied to the partial file, and the
    // result itself is not committed (the file the user named keeps what it had).
    plan_.write(*partial_, [this](std::ostream& out) {
      std::ifstream in(rows_path_, std::ios::binary);
      out << in.rdbuf();
      if (!in) throw std::runtime_error(rows_path_ + ": cannot read the rows back");
    });
    const std::string steps = commit_partial(*partial_, partial);
    s << (one ? " is in " : " are in ") << plan_.display_name(*partial_)
      << " (the run did not reach t_end; " << csv_name() << " was not written)" << steps;
  } catch (const std::exception& e) {
    s << " could not be written: " << e.what();
  }
  return s.str();
}

std::string RunOutputs::write_partial(const Model& model, const RunAttributes& run,
                                      const Trajectory& partial) {
  std::ostringstream s;
  const bool one = partial.t.size() == 1;
  s << "partial result: " << rows_phrase(static_cast<long>(partial.t.size()), partial.t.back());
  if (!partial_) {
    s << (one ? " was" : " were") << " not written (" << csv_name()
      << " is not a file: a stream, such as standard output, a device or a pipe, gets complete "
         "results only; give "
      << ask_for_file_ << " to keep them)";
    return s.str() + commit_partial(std::nullopt, partial);
  }
  try {
    write_result(*partial_, model, run, partial);
    const std::string steps = commit_partial(*partial_, partial);
    s << (one ? " is in " : " are in ") << plan_.display_name(*partial_)
      << " (the run did not reach t_end; " << csv_name() << " was not written)" << steps;
  } catch (const std::exception& e) {
    s << " could not be written: " << e.what();
  }
  return s.str();
}

}  // namespace condyn
