// A run's rows in an OutputMap's columns (dae/run/mapped_rows.hpp).

#include "dae/run/mapped_rows.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace condyn {

std::vector<int> point_indices(const OutputMap& map, const std::vector<std::string>& points) {
  std::vector<int> out;
  for (const auto& point : points) {
    const std::optional<int> index = map.point(point);
    if (!index) throw std::invalid_argument("[output] points: no point '" + point + "'");
    out.push_back(*index);
  }
  return out;
}

std::vector<std::string> point_columns(const OutputMap& map,
                                       const std::vector<std::string>& points) {
  std::vector<std::string> out;
  for (const auto& point : points) {
    // .x, .y (.z): the dimension's axes in order.
    for (int k = 0; k < map.dimension(); ++k)
      out.push_back(point + '.' + static_cast<char>('x' + k));
  }
  return out;
}

bool reads_reactions(const std::vector<Quantity>& quantities) {
  return std::find(quantities.begin(), quantities.end(), Quantity::reaction) != quantities.end();
}

MappedRows::MappedRows(const OutputMap& map, std::vector<int> points, bool reactions)
    : map_(map), points_(std::move(points)), reactions_(reactions) {}

void MappedRows::map(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                     const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                     Eigen::VectorXd& u_out, Eigen::VectorXd& v_out, Eigen::VectorXd& a_out,
                     Eigen::VectorXd& reaction_out, Eigen::VectorXd& points_out) {
  const auto size = [this](Quantity q) { return static_cast<Eigen::Index>(map_.names(q).size()); };
  u_out.resize(size(Quantity::displacement));
  map_.displacement(t, u, previous_, u_out);
  previous_ = u_out;
  v_out.resize(size(Quantity::velocity));
  map_.velocity(t, u, v, v_out);
  if (a.size() > 0) {
    a_out.resize(size(Quantity::acceleration));
    map_.acceleration(t, u, v, a, a_out);
  } else {
    a_out.resize(0);
  }
  reaction_out.setZero(size(Quantity::reaction));
  if (reactions_) map_.reaction(t, u, lambda, reaction_out);
  const Eigen::Index dim = map_.dimension();
  points_out.resize(dim * static_cast<Eigen::Index>(points_.size()));
  for (std::size_t k = 0; k < points_.size(); ++k) {
    Eigen::VectorXd at(dim);
    map_.point_position(points_[k], u, at);
    points_out.segment(dim * static_cast<Eigen::Index>(k), dim) = at;
  }
}

void MappedRows::map(TrajectoryRow& row) {
  Eigen::VectorXd u, v, a, reaction;
  map(row.t, row.u, row.v, row.acceleration, row.multiplier, u, v, a, reaction, row.points);
  row.u = std::move(u);
  row.v = std::move(v);
  row.acceleration = std::move(a);
  row.reaction = std::move(reaction);
}

Trajectory mapped_trajectory(const Model& model, Trajectory traj, const std::vector<int>& points,
                             bool reactions) {
  if (!model.outputs || traj.u.cols() == 0) return traj;
  const OutputMap& map = *model.outputs;
  MappedRows rows(map, points, reactions);
  const auto nt = static_cast<Eigen::Index>(traj.t.size());
  const auto columns = [&](Quantity q) { return static_cast<Eigen::Index>(map.names(q).size()); };
  const bool accelerations = traj.acceleration.cols() == nt && nt > 0;
  Eigen::MatrixXd u(columns(Quantity::displacement), nt), v(columns(Quantity::velocity), nt),
      a(accelerations ? columns(Quantity::acceleration) : 0, accelerations ? nt : 0),
      reaction(columns(Quantity::reaction), nt),
      at_points(map.dimension() * static_cast<Eigen::Index>(points.size()), nt);
  Eigen::VectorXd uk, vk, ak, rk, pk;
  const Eigen::VectorXd none;
  for (Eigen::Index k = 0; k < nt; ++k) {
    rows.map(traj.t[static_cast<std::size_t>(k)], traj.u.col(k), traj.v.col(k),
             accelerations ? Eigen::VectorXd(traj.acceleration.col(k)) : none,
             traj.multiplier.col(k), uk, vk, ak, rk, pk);
    u.col(k) = uk;
    v.col(k) = vk;
    if (accelerations) a.col(k) = ak;
    reaction.col(k) = rk;
    at_points.col(k) = pk;
  }
  traj.u = std::move(u);
  traj.v = std::move(v);
  traj.acceleration = std::move(a);
  traj.reaction = std::move(reaction);
  traj.points = std::move(at_points);
  return traj;
}

}  // namespace condyn
