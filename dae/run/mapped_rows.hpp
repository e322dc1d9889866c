#pragma once
/// A run's rows in the columns of a model's OutputMap (models/core/output_map.hpp): a
/// mechanism integrates natural coordinates, but its results show poses, velocities,
/// accelerations and joint reactions per body and joint (`crank.x`, `crank.vx`, `crank.ax`,
/// `hinge.fx`) and named points' positions (`crank.B.x`). What every reader of a mechanism's
/// results maps through: the CSV and HDF5 writers, Python, `check`, `compare`.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "dae/run/trajectory.hpp"
#include "models/core/model.hpp"
#include "models/core/output_map.hpp"

namespace condyn {

/// A run's rows in the columns of an OutputMap, mapped in row order: each row's displacement
/// continues from the previous row's (angles across ±π, a quaternion's sign). One object per
/// sequence of rows (a file, a check, a trajectory).
class MappedRows {
 public:
  /// `points`: the map's indices of the points whose positions each row gets. `reactions`: the
  /// rows' multipliers are those of the run's reactions (RunHooks::reactions) and the reaction
  /// columns are read; else they are left at 0 (the rows' multipliers may then be another
  /// scheme's own).
  MappedRows(const OutputMap& map, std::vector<int> points, bool reactions);
  /// Replaces the row's u, v, acceleration (when it has one) and reaction by the map's
  /// displacement, velocity, acceleration and reaction columns (the reaction from the row's
  /// multipliers) and sets its points (dimension() per point).
  void map(TrajectoryRow& row);
  /// The same for the state (t, u, v, a, λ), into the given vectors (`a` empty: no
  /// acceleration).
  void map(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
           const Eigen::VectorXd& lambda, Eigen::VectorXd& u_out, Eigen::VectorXd& v_out,
           Eigen::VectorXd& a_out, Eigen::VectorXd& reaction_out, Eigen::VectorXd& points_out);

 private:
  const OutputMap& map_;
  std::vector<int> points_;
  bool reactions_;
  Eigen::VectorXd previous_;  ///< the previous row's displacement columns (empty at the first)
};

/// `traj` with u, v, acceleration (when it has one) and reaction in the columns of the model's
/// OutputMap and its points (`points`: the map's indices) set; `traj` itself without a map.
/// A streamed run's trajectory (no u) is returned as it is. `reactions` as for MappedRows.
[[nodiscard]] Trajectory mapped_trajectory(const Model& model, Trajectory traj,
                                           const std::vector<int>& points, bool reactions);
/// Whether `quantities` read the rows' reactions (the mapped reaction columns).
[[nodiscard]] bool reads_reactions(const std::vector<Quantity>& quantities);

/// The map's indices of the named points `points` ("body.point", [output] points), in order.
/// Throws std::invalid_argument naming one the map does not have (build_model refuses it first).
[[nodiscard]] std::vector<int> point_indices(const OutputMap& map,
                                             const std::vector<std::string>& points);
/// Their columns' names, `body.point.x`, `.y` (`.z`): dimension() per point.
[[nodiscard]] std::vector<std::string> point_columns(const OutputMap& map,
                                                     const std::vector<std::string>& points);

}  // namespace condyn
