#pragma once
/// The CSV of the contract (scene-format.md, "Output"): first column t, then the requested
/// quantities in the order the scene lists them.

#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "dae/run/solve_result.hpp"
#include "dae/run/trajectory.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_spec.hpp"
#include "src/output/hdf5_output.hpp"
#include "src/output/output_files.hpp"
#include "src/output/output_format.hpp"
#include "src/output/row_writer.hpp"

namespace condyn {

/// A failed run's message: describe_failure's, then, on a line of its own, where its rows went
/// (`partial_note`, from RunOutputs::keep; none when empty).
[[nodiscard]] std::string failure_message(const SolveResult& result, double t_end,
                                          const std::string& partial_note);

/// The per-step drift log (run --steps-out): columns t, drift_position, drift_velocity, one row per
/// internal step of the integrator.
void write_steps_csv(std::ostream& out, const Trajectory& traj);

/// The files of `condyn run`, checked before the integration (OutputPlan): the CSV of the
/// [output] quantities (to --out, else [output] file, else SCENE-STEM.csv in the current folder),
/// the drift log (--steps-out) and, for a failed run, FILE.partial.csv beside the CSV (and
/// STEPS.partial.csv beside the drift log, with the steps before the failure). None may be
/// the scene, a file it names (`inputs`: SceneSpec::input_files) or another output. `[output]
/// file` is relative to the scene's folder, as every path a scene names. A CSV going to a stream
/// (standard output, a device, a FIFO) gets complete results only: a failed run writes nothing
/// there and no partial file. Throws OutputError (bad paths).
class RunOutputs {
 public:
  /// `scene`: the scene file ("" for a scene that is no file, a Python dict: then `out_flag` must
  /// name the result); `out_source`: what messages call `out_flag` ("out" for condyn.run).
  RunOutputs(const std::string& scene, const std::string& out_flag, const OutputSpec& output,
             const std::string& steps_out, const std::vector<std::string>& inputs = {},
             const std::string& out_source = "--out");

  /// Where every line but the data goes: standard error when an output is standard output.
  [[nodiscard]] std::ostream& messages() const;
  /// The CSV's name for messages ("standard output" for `-`).
  [[nodiscard]] std::string csv_name() const;
  [[nodiscard]] bool has_steps() const { return steps_.has_value(); }
  [[nodiscard]] std::string steps_name() const;

  /// What `condyn run` keeps of a run, its rows given to stream_rows (when it was called) or all
  /// in `traj`: a finished run's result and drift log, committed (finish_stream or write); a
  /// failed run's rows in the partial files (finish_stream_partial or write_partial, none for a
  /// run without rows). Returns the sentence saying where a failed run's rows went ("" for a
  /// finished run, or a failed one without rows).
  [[nodiscard]] std::string keep(const Model& model, const RunAttributes& run,
                                 const Trajectory& traj, bool finished);

  /// A finished run: the result (HDF5 for a name ending in .h5, .hdf5 or .hdf) and the drift log,
  /// committed together.
  void write(const Model& model, const RunAttributes& run, const Trajectory& traj);
  /// A failed run: its rows into FILE.partial.csv (the CSV and drift log are left as they were);
  /// returns the sentence saying where they went, or why they were not written.
  [[nodiscard]] std::string write_partial(const Model& model, const RunAttributes& run,
                                          const Trajectory& partial);

  /// True when the result goes to a regular file, whose rows can then be written as the run
  /// computes them (stream_rows). A stream (standard output, a device, a pipe) gets complete
  /// results only, at the end (write).
  [[nodiscard]] bool can_stream() const { return partial_.has_value(); }
  /// Opens the result file (its temporary file) for the run's rows; the sink to give the run
  /// (RunHooks::on_row). The model must outlive this object's use of the sink.
  [[nodiscard]] std::function<void(const TrajectoryRow&)> stream_rows(const Model& model);
  /// A finished streamed run: completes the file, writes the drift log, commits both.
  void finish_stream(const RunAttributes& run, const Trajectory& traj);
  /// The partial files of an earlier failed run (FILE.partial.csv, STEPS.partial.csv) that a
  /// finished run removed when it committed its own files: they no longer describe its result.
  [[nodiscard]] const std::vector<std::string>& removed_partials() const { return removed_; }
  /// A failed streamed run: completes the rows written so far and keeps them in the partial file
  /// (when there is more than the initial row; else nothing is kept and "" is returned); returns
  /// the sentence saying where they went, as write_partial.
  [[nodiscard]] std::string finish_stream_partial(const RunAttributes& run,
                                                  const Trajectory& partial);

 private:
  /// Commits a failed run's partial rows (`rows`, written) together with its drift log
  /// (--steps-out) in STEPS.partial.csv; returns "; the drift at its N internal steps is in …"
  /// for the partial result's sentence, or "" without a log.
  [[nodiscard]] std::string commit_partial(std::optional<OutputPlan::Id> rows,
                                           const Trajectory& partial);
  /// Commits the result (written) with the drift log of `traj` when one is asked for, and removes
  /// the partial files an earlier failed run left under the same names.
  void commit_result(const Trajectory& traj);
  /// The result into output `id`, in the format its name asks for.
  void write_result(OutputPlan::Id id, const Model& model, const RunAttributes& run,
                    const Trajectory& traj);

  OutputSpec output_;
  /// How a message asks for a result file: "--out FILE" (the CLI) or "out=FILE" (condyn.run).
  std::string ask_for_file_;
  OutputPlan plan_;
  FileFormat format_ = FileFormat::csv;  ///< the result's (and its partial file's)
  std::unique_ptr<RowWriter> rows_;      ///< a streamed run's result file
  std::string rows_path_;                ///< its temporary file
  OutputPlan::Id csv_ = 0;
  std::optional<OutputPlan::Id> steps_, partial_, steps_partial_;
  std::vector<std::string> removed_;  ///< removed_partials()
};

}  // namespace condyn
