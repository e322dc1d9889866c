#pragma once
/// A streamed run's result file, written row by row as the integration reaches each output time
/// (RunHooks::on_row): nothing of size DOFs x output times is held. CSV (the same bytes as the
/// whole-trajectory writer) or HDF5 (the same datasets, shapes and attributes; the row dimension
/// extendible and chunked), chosen by the path as for a whole result.

#include <memory>
#include <string>

#include "dae/run/trajectory.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_spec.hpp"
#include "src/output/hdf5_output.hpp"

namespace condyn {

class RowWriter {
 public:
  virtual ~RowWriter() = default;
  /// Appends one output row. Throws std::runtime_error when the file cannot be written.
  virtual void row(const TrajectoryRow& row) = 0;
  /// Completes the file with the run's attributes (HDF5 root attributes; the CSV has none): after
  /// it, the file at the path is whole. Throws std::runtime_error.
  virtual void finish(const RunAttributes& run) = 0;
  [[nodiscard]] long rows() const { return rows_; }

 protected:
  long rows_ = 0;
};

/// Opens `path` (created or truncated) for the run's rows: HDF5 when `hdf5`, else CSV. The model
/// and output spec must outlive the writer.
[[nodiscard]] std::unique_ptr<RowWriter> open_row_writer(const std::string& path, bool hdf5,
                                                         const Model& model,
                                                         const OutputSpec& output);

}  // namespace condyn
