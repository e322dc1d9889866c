// A mechanism's Model ([model] type = "multibody"): the system, rows and output map of
// build_multibody (models/systems/multibody_system.hpp), and its start checked against the
// joints and drives at t = 0 within 1e-8 of the model's size (docs/scenes.md, "Mechanisms of
// rigid bodies"), or projected onto them keeping the values [initial] keep names.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "models/assembly/model_builder.hpp"
#include "models/systems/multibody_system.hpp"

namespace condyn {

namespace {

// Above this many named points the model's size is the diagonal of their bounding box (at most
// √3 times their largest distance) instead of the largest distance itself, whose pairs grow
// with the square of the count.
constexpr std::size_t kExactDiameterPoints = 4096;

Eigen::Vector3d as_vector(const Mechanism::Vec3& v) { return {v[0], v[1], v[2]}; }

/// Every named point of the mechanism (ground's included) in global coordinates at t = 0.
std::vector<Eigen::Vector3d> named_points(const Mechanism& m) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : m.ground_points) out.push_back(as_vector(p.at));
  for (const auto& b : m.bodies) {
    for (const auto& p : b.points)
      out.push_back(as_vector(b.position) + b.orientation * as_vector(p.at));
  }
  return out;
}

}  // namespace

double mechanism_size(const Mechanism& m) {
  const auto points = named_points(m);
  double size = 0.0;
  if (points.size() <= kExactDiameterPoints) {
    for (std::size_t i = 0; i < points.size(); ++i)
      for (std::size_t j = i + 1; j < points.size(); ++j)
        size = std::max(size, (points[i] - points[j]).norm());
  } else {
    Eigen::Vector3d lo = points.front(), hi = points.front();
    for (const auto& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    size = (hi - lo).norm();
  }
  return size > 0.0 ? size : 1.0;  // one point (or all at one place): 1, as the contract says
}

void ModelBuilder::build_mechanism() {
  const Mechanism& m = *spec_.model.mechanism;
  MultibodyParts parts = build_multibody(m);
  set_dofs(parts.coordinate_names);
  model_.system = parts.system;
  model_.nonlinear = true;
  model_.outputs = parts.outputs;
  model_.constraints = std::move(parts.rows);
  for (const auto& joint : m.joints)
    if (joint.drive) model_.drives.push_back(*joint.drive);
  row_joint_ = std::move(parts.row_joint);
  row_rheonomic_ = std::move(parts.row_rheonomic);
  base_u0_ = std::move(parts.q0);
  base_v0_ = std::move(parts.v0);
  model_.description =
      std::string(m.dimension == 2 ? "planar" : "spatial") +
      " mechanism: " + std::to_string(m.bodies.size()) + " rigid bod" +
      (m.bodies.size() == 1 ? "y" : "ies") + ", " + std::to_string(m.joints.size()) + " joint" +
      (m.joints.size() == 1 ? "" : "s") + ", " + std::to_string(m.forces.size()) +
      " force element" + (m.forces.size() == 1 ? "" : "s") + " (natural coordinates)";
}

/// BuildReport::joints: per joint its type, bodies and rows, classed as the chapter classes
/// constraints (every joint row is holonomic, position level; a drive's rows depend on t). The
/// rows as the model keeps them, after redundant = "drop": those kept, then those dropped.
void ModelBuilder::report_joints() {
  const Mechanism& m = *spec_.model.mechanism;
  const auto body_name = [&](int b) {
    return b == Mechanism::kGround ? std::string("ground")
                                   : m.bodies[static_cast<std::size_t>(b)].name;
  };
  // Each joint's rows, in one pass over the rows (a pass per joint was quadratic on a chain).
  std::vector<std::vector<std::size_t>> rows_of(m.joints.size());
  for (std::size_t i = 0; i < row_joint_.size(); ++i) {
    const int j = row_joint_[i];
    if (j >= 0 && static_cast<std::size_t>(j) < rows_of.size())
      rows_of[static_cast<std::size_t>(j)].push_back(i);
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const auto& joint = m.joints[j];
    std::vector<std::string> rows;
    bool rheonomic = false;
    for (const std::size_t i : rows_of[j]) {
      rows.push_back(model_.constraints[i].name);
      rheonomic = rheonomic || row_rheonomic_[i];
    }
    std::vector<std::string> dropped;
    for (const auto& [row_joint, name] : dropped_joint_rows_)
      if (row_joint == static_cast<int>(j)) dropped.push_back(name);
    const auto listed = [](const std::vector<std::string>& names) {
      std::string text;
      for (const auto& r : names) text += (text.empty() ? "" : ", ") + r;
      return text;
    };
    std::string rows_text = std::to_string(rows.size()) + " row" + (rows.size() == 1 ? "" : "s") +
                            (rows.empty() ? "" : " (" + listed(rows) + ")");
    if (!dropped.empty()) {
      rows_text +=
          ", " + std::to_string(dropped.size()) + " dropped as redundant (" + listed(dropped) + ")";
    }
    report_.joints.push_back(joint.name + " (" + to_string(joint.type) + ", " +
                             body_name(joint.bodies[0]) + " - " + body_name(joint.bodies[1]) +
                             "): " + rows_text + ", holonomic, " +
                             (rheonomic ? "rheonomic (driven)" : "scleronomic"));
  }
}

}  // namespace condyn
