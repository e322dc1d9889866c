// Result files written row by row (src/output/row_writer.hpp).

#include "src/output/row_writer.hpp"

#include <algorithm>
#include <fstream>
#include <optional>
#include <vector>

#include "src/output/csv_rows.hpp"
#include "src/output/hdf5_parts.hpp"
#include "src/output/output_columns.hpp"

namespace condyn {

namespace {

/// The row a writer writes: the run's own, or its copy in the model's OutputMap columns.
class RowView {
 public:
  RowView(const OutputColumns& columns, const OutputSpec& output) {
    if (columns.mapped()) {
      mapper_.emplace(
          *columns.map(), columns.points(),
          reads_reactions(with_derived_quantities(output.quantities, columns.model().derived)));
    }
  }
  const TrajectoryRow& operator()(const TrajectoryRow& row) {
    if (!mapper_) return row;
    mapped_ = row;
    mapper_->map(mapped_);
    return mapped_;
  }

 private:
  std::optional<MappedRows> mapper_;
  TrajectoryRow mapped_;
};

class CsvRowWriter final : public RowWriter {
 public:
  CsvRowWriter(const std::string& path, const Model& model, const OutputSpec& output)
      : model_(model),
        output_(output),
        columns_(model, output),
        view_(columns_, output),
        absolute_(std::find(output.quantities.begin(), output.quantities.end(),
                            Quantity::absolute_acceleration) != output.quantities.end()),
        path_(path) {
    out_.open(path, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error(path + ": cannot open the output for writing");
    out_ << csv_header(output, columns_) << "\n";
  }

  void row(const TrajectoryRow& run_row) override {
    const TrajectoryRow& r = view_(run_row);
    if (absolute_) absolute_acceleration_ = model_.absolute_acceleration(r.t, r.acceleration);
    const CsvRow view{r.t,
                      r.u,
                      r.v,
                      r.acceleration,
                      absolute_acceleration_,
                      r.reaction,
                      r.multiplier,
                      r.drift_position,
                      r.drift_velocity,
                      r.balance ? &*r.balance : nullptr,
                      r.points,
                      r.near_singular};
    line_.clear();
    append_csv_row(line_, output_, columns_, view);
    out_ << line_ << "\n";
    if (!out_) throw std::runtime_error(path_ + ": writing the output failed");
    ++rows_;
  }

  void finish(const RunAttributes& /*run*/) override {
    out_.close();
    if (!out_) throw std::runtime_error(path_ + ": writing the output failed");
  }

 private:
  const Model& model_;
  const OutputSpec& output_;
  OutputColumns columns_;
  RowView view_;
  bool absolute_ = false;
  Eigen::VectorXd absolute_acceleration_;
  std::string path_, line_;
  std::ofstream out_;
};

/// One dataset of `cols` doubles per row (`vector`: one double per row, a 1-D dataset),
/// extendible along the rows and chunked so that a chunk stays near 1 MB whatever the width; rows
/// are buffered a chunk at a time. A dataset of no columns (no DOF selected, no constraint) holds
/// no data: it is created whole, rows x 0, when the series is finished.
class Series {
 public:
  Series(hid_t file, const char* name, hsize_t cols, bool vector)
      : file_(file), name_(name), cols_(vector ? 1 : cols), vector_(vector) {
    if (cols_ == 0) return;
    constexpr hsize_t kChunkDoubles = 131072;  // 1 MB
    chunk_cols_ = std::max<hsize_t>(1, std::min(cols_, kChunkDoubles));
    chunk_rows_ = std::max<hsize_t>(1, std::min<hsize_t>(64, kChunkDoubles / chunk_cols_));
    const int rank = vector ? 1 : 2;
    const hsize_t dims[2] = {0, cols_}, max[2] = {H5S_UNLIMITED, cols_};
    const hdf5::Handle space(H5Screate_simple(rank, dims, max), H5Sclose, "H5Screate_simple");
    const hdf5::Handle props(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate");
    const hsize_t chunk[2] = {chunk_rows_, chunk_cols_};
    hdf5::check(H5Pset_chunk(props.id(), rank, chunk), "H5Pset_chunk");
    set_ = H5Dcreate2(file, name, H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT);
    if (set_ < 0) throw std::runtime_error(std::string("HDF5: H5Dcreate2 failed for ") + name);
  }
  Series(const Series&) = delete;
  Series& operator=(const Series&) = delete;
  ~Series() {
    if (set_ >= 0) H5Dclose(set_);
  }

  /// The row's values go to the buffer; a full buffer is written.
  template <class Get>
  void append(const Get& get) {
    for (hsize_t c = 0; c < cols_; ++c) buffer_.push_back(get(c));
    ++buffered_;
    if (buffered_ == chunk_rows_ && cols_ > 0) flush();
  }

  /// Writes what is buffered; `last`: the series is complete (a dataset of no columns is
  /// created now, rows x 0).
  void flush(bool last = false) {
    if (last && cols_ == 0) {
      const hsize_t dims[2] = {written_ + buffered_, 0};
      const hdf5::Handle space(H5Screate_simple(2, dims, nullptr), H5Sclose, "H5Screate_simple");
      const hdf5::Handle set(H5Dcreate2(file_, name_.c_str(), H5T_IEEE_F64LE, space.id(),
                                        H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             H5Dclose, "H5Dcreate2");
    }
    if (buffered_ == 0) return;
    const hsize_t total[2] = {written_ + buffered_, cols_};
    if (cols_ > 0) {
      hdf5::check(H5Dset_extent(set_, total), "H5Dset_extent");
      const hdf5::Handle file_space(H5Dget_space(set_), H5Sclose, "H5Dget_space");
      const hsize_t start[2] = {written_, 0}, count[2] = {buffered_, cols_};
      hdf5::check(
          H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, start, nullptr, count, nullptr),
          "H5Sselect_hyperslab");
      const hdf5::Handle memory(H5Screate_simple(vector_ ? 1 : 2, count, nullptr), H5Sclose,
                                "H5Screate_simple");
      hdf5::check(H5Dwrite(set_, H5T_NATIVE_DOUBLE, memory.id(), file_space.id(), H5P_DEFAULT,
                           buffer_.data()),
                  "H5Dwrite");
    }
    written_ += buffered_;
    buffered_ = 0;
    buffer_.clear();
  }

 private:
  hid_t file_;
  std::string name_;
  hsize_t cols_;
  bool vector_;
  hsize_t chunk_rows_ = 1, chunk_cols_ = 1;
  hid_t set_ = -1;
  std::vector<double> buffer_;
  hsize_t buffered_ = 0, written_ = 0;
};

class Hdf5RowWriter final : public RowWriter {
 public:
  Hdf5RowWriter(const std::string& path, const Model& model, const OutputSpec& output)
      : model_(model), columns_(model, output), view_(columns_, output), path_(path) {
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file_ < 0) throw std::runtime_error(path + ": HDF5 cannot create the file");
    const auto width = [this](Quantity q) {
      return static_cast<hsize_t>(columns_.shown(q).size());
    };
    t_ = std::make_unique<Series>(file_, "t", 0, true);
    for (Quantity q : output.quantities) {
      switch (q) {
        case Quantity::displacement:
          u_ = std::make_unique<Series>(file_, "displacement", width(q), false);
          break;
        case Quantity::velocity:
          v_ = std::make_unique<Series>(file_, "velocity", width(q), false);
          break;
        case Quantity::acceleration:
          a_ = std::make_unique<Series>(file_, "acceleration", width(q), false);
          break;
        case Quantity::absolute_acceleration:
          a_abs_ = std::make_unique<Series>(file_, "absolute_acceleration", width(q), false);
          break;
        case Quantity::reaction:
          reaction_ = std::make_unique<Series>(file_, "reaction", width(q), false);
          break;
        case Quantity::multiplier:
          multiplier_ = std::make_unique<Series>(
              file_, "multiplier", static_cast<hsize_t>(model.constraint_count()), false);
          break;
        case Quantity::drift:
          drift_ = std::make_unique<Series>(file_, "drift", 2, false);
          break;
        case Quantity::energy:
          energy_ = std::make_unique<Series>(file_, "energy", kEnergyColumns.size(), false);
          break;
      }
    }
    if (!columns_.points().empty()) {
      points_ = std::make_unique<Series>(
          file_, "points", static_cast<hsize_t>(columns_.point_columns().size()), false);
    }
    if (!model.derived.empty()) {
      derived_ = std::make_unique<Series>(file_, "derived", model.derived.size(), false);
      std::vector<std::string> names;
      for (const auto& d : model.derived) names.push_back(d.name);
      hdf5::put_strings(file_, "derived_names", names);
    }
    if (columns_.near_singular()) {
      near_singular_ = std::make_unique<Series>(file_, "near_singular", 0, true);
    }
    hdf5::put_column_names(file_, columns_);
    if (energy_) hdf5::put_strings(file_, "energy_columns", energy_column_names());
  }
  Hdf5RowWriter(const Hdf5RowWriter&) = delete;
  Hdf5RowWriter& operator=(const Hdf5RowWriter&) = delete;
  ~Hdf5RowWriter() override { close(); }

  void row(const TrajectoryRow& run_row) override {
    const TrajectoryRow& r = view_(run_row);
    t_->append([&](hsize_t) { return r.t; });
    const auto dofs = [this](Quantity q, Series& s, const Eigen::VectorXd& x) {
      const std::vector<int>& shown = columns_.shown(q);
      s.append([&](hsize_t c) { return x[shown[c]]; });
    };
    if (u_) dofs(Quantity::displacement, *u_, r.u);
    if (v_) dofs(Quantity::velocity, *v_, r.v);
    if (a_) dofs(Quantity::acceleration, *a_, r.acceleration);
    // Computed once for the row: its columns and the derived columns' acc_abs_ terms.
    const Eigen::VectorXd absolute =
        a_abs_ ? model_.absolute_acceleration(r.t, r.acceleration) : Eigen::VectorXd();
    if (a_abs_) dofs(Quantity::absolute_acceleration, *a_abs_, absolute);
    if (reaction_) dofs(Quantity::reaction, *reaction_, r.reaction);
    if (multiplier_) {
      multiplier_->append([&](hsize_t c) { return r.multiplier[static_cast<Eigen::Index>(c)]; });
    }
    if (drift_)
      drift_->append([&](hsize_t c) { return c == 0 ? r.drift_position : r.drift_velocity; });
    if (energy_) {
      if (!r.balance) throw std::logic_error("an energy row without a balance");
      energy_->append([&](hsize_t c) { return energy_column(*r.balance, c); });
    }
    if (points_) points_->append([&](hsize_t c) { return r.points[static_cast<Eigen::Index>(c)]; });
    if (derived_) {
      const Eigen::VectorXd derived =
          model_.derived_values(r.t, r.u, r.v, r.acceleration, r.reaction, absolute);
      derived_->append([&](hsize_t c) { return derived[static_cast<Eigen::Index>(c)]; });
    }
    if (near_singular_)
      near_singular_->append([&](hsize_t) { return r.near_singular ? 1.0 : 0.0; });
    ++rows_;
  }

  void finish(const RunAttributes& run) override {
    hdf5::put_run_attributes(file_, run);
    for (Series* s :
         {t_.get(), u_.get(), v_.get(), a_.get(), a_abs_.get(), reaction_.get(), multiplier_.get(),
          drift_.get(), energy_.get(), points_.get(), derived_.get(), near_singular_.get()}) {
      if (s != nullptr) s->flush(true);
    }
    close();
    if (failed_) throw std::runtime_error(path_ + ": HDF5 could not complete the file");
  }

 private:
  void close() {
    t_.reset();
    u_.reset();
    v_.reset();
    a_.reset();
    a_abs_.reset();
    reaction_.reset();
    multiplier_.reset();
    drift_.reset();
    energy_.reset();
    points_.reset();
    derived_.reset();
    near_singular_.reset();
    if (file_ >= 0) {
      failed_ = H5Fclose(file_) < 0;
      file_ = -1;
    }
  }

  const Model& model_;
  OutputColumns columns_;
  RowView view_;
  std::string path_;
  hid_t file_ = -1;
  std::unique_ptr<Series> t_, u_, v_, a_, a_abs_, reaction_, multiplier_, drift_, energy_, points_,
      derived_, near_singular_;
  bool failed_ = false;
};

}  // namespace

std::unique_ptr<RowWriter> open_row_writer(const std::string& path, bool hdf5, const Model& model,
                                           const OutputSpec& output) {
  if (hdf5) return std::make_unique<Hdf5RowWriter>(path, model, output);
  return std::make_unique<CsvRowWriter>(path, model, output);
}

}  // namespace condyn
