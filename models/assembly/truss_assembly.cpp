// Truss assembly: nodes to DOFs, members to bars and rods, M and K of the truss, gravity.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "models/assembly/model_builder.hpp"

namespace condyn {

namespace {

/// The small-displacement stiffness and damping of the bars: k = EA/L and the dashpot's c along
/// the unit axis at the reference positions, as triplets on the DOFs (dim per node).
void small_displacement_bars(const std::vector<std::array<double, 3>>& nodes,
                             const std::vector<PointMassLayout::Bar>& bars, int dim,
                             std::vector<Eigen::Triplet<double>>& k_trip,
                             std::vector<Eigen::Triplet<double>>& c_trip) {
  for (const auto& b : bars) {
    const auto& pi = nodes[static_cast<std::size_t>(b.i)];
    const auto& pj = nodes[static_cast<std::size_t>(b.j)];
    const double distance = std::hypot(pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]);
    std::vector<int> idx;
    std::vector<double> dir;
    for (int sign : {-1, 1}) {
      for (int d = 0; d < dim; ++d) {
        idx.push_back((sign < 0 ? b.i : b.j) * dim + d);
        dir.push_back(sign * (pj[static_cast<std::size_t>(d)] - pi[static_cast<std::size_t>(d)]) /
                      distance);
      }
    }
    for (std::size_t a = 0; a < idx.size(); ++a) {
      for (std::size_t c = 0; c < idx.size(); ++c) {
        k_trip.emplace_back(idx[a], idx[c], b.EA / b.length * dir[a] * dir[c]);
        if (b.c != 0.0) c_trip.emplace_back(idx[a], idx[c], b.c * dir[a] * dir[c]);
      }
    }
  }
}

}  // namespace

void ModelBuilder::build_truss() {
  const auto& m = spec_.model;
  const int dim = m.dimension;
  static constexpr std::array<const char*, 3> kAxes = {"ux", "uy", "uz"};
  std::vector<std::string> names;
  for (std::size_t k = 1; k <= m.nodes.size(); ++k) {
    for (int d = 0; d < dim; ++d)
      names.push_back(kAxes[static_cast<std::size_t>(d)] + std::to_string(k));
  }
  set_dofs(names);
  const int n = model_.dofs();
  double extent = 0.0;
  for (const auto& p : m.nodes) {
    for (double x : p) extent = std::max(extent, std::abs(x));
  }
  nonlinear_truss_ = m.geometry == ModelSpec::Geometry::nonlinear;
  for (std::size_t e = 0; e < m.members.size(); ++e) {
    const auto& mem = m.members[e];
    const auto& pi = m.nodes[static_cast<std::size_t>(mem.node_i - 1)];
    const auto& pj = m.nodes[static_cast<std::size_t>(mem.node_j - 1)];
    // hypot: no overflow or underflow of the squares for coordinates near the double range.
    const double distance = std::hypot(pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]);
    if (!std::isfinite(distance)) {
      fail(mem.where, "member joins nodes " + std::to_string(mem.node_i) + " and " +
                          std::to_string(mem.node_j) +
                          ", whose distance overflows the double range (coordinates too large)");
    }
    if (distance <= 1e-12 * std::max(extent, 1e-300)) {  // no direction, whatever `length` says
      fail(mem.where, "member joins nodes " + std::to_string(mem.node_i) + " and " +
                          std::to_string(mem.node_j) + ", which coincide (zero length)");
    }
    const double length = mem.length.value_or(distance);  // rest length (bar) or length (rod)
    if (!mem.rigid && !std::isfinite(mem.EA / length)) {
      fail({mem.where.path + ".EA", mem.where.line},
           "EA / length = " + fmt(mem.EA) + " / " + fmt(length) +
               " overflows the double range: the stiffness would be infinite");
    }
    const PointMassLayout::Bar bar{mem.node_i - 1, mem.node_j - 1, mem.EA, length, mem.c};
    if (mem.rigid) {
      layout_.rods.push_back(bar);
      rod_where_.push_back(mem.where);
      nonlinear_truss_ = true;
    } else {
      layout_.bars.push_back(bar);
    }
  }
  layout_.dimension = dim;
  layout_.nodes = m.nodes;
  layout_.masses = m.masses;
  layout_.nonlinear_geometry = m.geometry == ModelSpec::Geometry::nonlinear;
  // The linear model's K and C (its own K for linear geometry, where L is the nodes' distance: a
  // rest length needs large displacements).
  std::vector<Eigen::Triplet<double>> k_trip, c_trip, m_trip;
  small_displacement_bars(m.nodes, layout_.bars, dim, k_trip, c_trip);
  for (std::size_t k = 0; k < m.nodes.size(); ++k) {
    for (int d = 0; d < dim; ++d) {
      if (m.masses[k] != 0.0) {
        m_trip.emplace_back(static_cast<int>(k) * dim + d, static_cast<int>(k) * dim + d,
                            m.masses[k]);
      }
    }
  }
  model_.K.edit().resize(n, n);
  model_.K.edit().setFromTriplets(k_trip.begin(), k_trip.end());
  model_.M.resize(n, n);
  model_.M.setFromTriplets(m_trip.begin(), m_trip.end());
  model_.C.resize(n, n);
  model_.C.setFromTriplets(c_trip.begin(), c_trip.end());
  // Gravity: a constant load m g on every node with mass, before the scene's loads.
  for (std::size_t k = 0; k < m.nodes.size() && !m.gravity.empty(); ++k) {
    for (int d = 0; d < dim; ++d) {
      const double w = m.masses[k] * m.gravity[static_cast<std::size_t>(d)];
      if (!std::isfinite(w)) {
        fail({"model.gravity", m.where.line}, "the weight of node " + std::to_string(k + 1) +
                                                  " (mass " + fmt(m.masses[k]) + " times " +
                                                  fmt(m.gravity[static_cast<std::size_t>(d)]) +
                                                  ") overflows the double range");
      }
      if (w != 0.0) {
        model_.loads.push_back(Load{static_cast<int>(k) * dim + d, TimeFunction::constant(w), {}});
      }
    }
  }
}

}  // namespace condyn
