// [[body]] of a multibody model (docs/scenes.md, "Mechanisms of rigid bodies"): mass, inertia,
// pose and velocity at t = 0, named points and axes. The inertia is checked as a rigid body's
// must be: positive definite, and in 3D its principal moments satisfy the triangle inequality
// (each at most the sum of the other two; equal for a lamina).

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include "models/core/eigen_decompositions.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

namespace {

// Roundoff allowed in the inertia checks, relative to the largest principal moment: a lamina's
// Izz = Ixx + Iyy written in decimal (or a rotated tensor's eigenvalues) is off by a few ulps.
constexpr double kInertiaRoundoff = 64 * std::numeric_limits<double>::epsilon();
// A quaternion's norm may differ from 1 by this much (relative): 17 written digits give about
// 1e-16; a quaternion written to fewer digits is refused rather than normalized, as it more likely
// holds a typo than a rounding (docs/scenes.md says so; { axis, angle } takes any axis length).
constexpr double kUnitQuaternion = 1e-12;

}  // namespace

namespace {

/// The principal moments' checks: positive, and each at most the sum of the other two.
void check_principal_moments(const SceneReader& r, const toml::node& node, const std::string& p,
                             const Eigen::Vector3d& moments) {
  const double largest = moments.cwiseAbs().maxCoeff();
  const double slack = kInertiaRoundoff * largest;
  if (!(moments.minCoeff() > slack)) {
    r.fail(node, p,
           "is not positive definite (principal moments " + TomlAccess::fmt(moments[0]) + ", " +
               TomlAccess::fmt(moments[1]) + ", " + TomlAccess::fmt(moments[2]) +
               "): a rigid body has a positive moment of inertia about every axis");
  }
  for (int i = 0; i < 3; ++i) {
    const double others = moments[(i + 1) % 3] + moments[(i + 2) % 3];
    if (moments[i] > others + slack) {
      r.fail(node, p,
             "violates the triangle inequality: principal moment " + TomlAccess::fmt(moments[i]) +
                 " exceeds the sum of the other two, " + TomlAccess::fmt(others) +
                 " (no mass distribution has it; a lamina has equality)");
    }
  }
}

/// 2D: a number > 0 (about the centre of mass, in (2, 2)). 3D: [Ixx, Iyy, Izz] or a symmetric
/// 3x3 list.
Eigen::Matrix3d read_inertia(const SceneReader& r, const toml::node& node, const std::string& p,
                             int dim) {
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  if (dim == 2) {
    if (!node.is_number()) {
      r.fail(node, p, "a planar body's inertia is one number (about the centre of mass, > 0)");
    }
    I(2, 2) = r.positive(node, p);
    return I;
  }
  const auto* arr = node.as_array();
  if (arr != nullptr && arr->size() == 3 && arr->get(0)->is_number()) {
    const auto d = r.numbers(node, p);
    I.diagonal() << d[0], d[1], d[2];
    check_principal_moments(r, node, p, I.diagonal());
    return I;
  }
  const auto rows = arr != nullptr ? r.dense_matrix(node, p) : std::vector<std::vector<double>>{};
  if (rows.size() != 3 || rows[0].size() != 3 || rows[1].size() != 3 || rows[2].size() != 3) {
    r.fail(node, p,
           "a spatial body's inertia is [Ixx, Iyy, Izz] (principal axes along the body frame) or "
           "a 3x3 list of rows");
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      I(i, j) = rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  const double size = I.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (!(std::abs(I(i, j) - I(j, i)) <= kInertiaRoundoff * size)) {
        r.fail(node, p,
               "is not symmetric: entry (" + std::to_string(i + 1) + ", " + std::to_string(j + 1) +
                   ") = " + TomlAccess::fmt(I(i, j)) + " but (" + std::to_string(j + 1) + ", " +
                   std::to_string(i + 1) + ") = " + TomlAccess::fmt(I(j, i)));
      }
    }
  }
  I = 0.5 * (I + I.transpose()).eval();
  check_principal_moments(r, node, p,
                          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues());
  return I;
}

/// orientation = { quaternion = [w, x, y, z] } (unit, refused otherwise) or { axis, angle }.
Eigen::Quaterniond read_orientation(const SceneReader& r, const toml::node& node,
                                    const std::string& p) {
  const auto& t = r.table(node, p);
  r.check_keys(t, p, {"quaternion", "axis", "angle"});
  if (const auto* q = t.get("quaternion")) {
    if (t.contains("axis") || t.contains("angle")) {
      r.fail(node, p, "give either quaternion or { axis, angle }, not both");
    }
    const std::string qp = TomlAccess::join(p, "quaternion");
    const auto v = r.numbers(*q, qp);
    if (v.size() != 4) r.fail(*q, qp, "a quaternion is [w, x, y, z] (4 numbers)");
    Eigen::Quaterniond out(v[0], v[1], v[2], v[3]);
    if (!(std::abs(out.norm() - 1.0) <= kUnitQuaternion)) {
      r.fail(*q, qp,
             "is not a unit quaternion (norm " + TomlAccess::fmt(out.norm()) +
                 "): write it to full precision, or give { axis = [...], angle = a }");
    }
    return out;
  }
  const auto& axis_node = r.required(t, p, "axis");
  const std::string ap = TomlAccess::join(p, "axis");
  const auto axis = r.numbers(axis_node, ap);
  if (axis.size() != 3) r.fail(axis_node, ap, "an axis in 3D has 3 components");
  const Eigen::Vector3d a(axis[0], axis[1], axis[2]);
  if (!(a.norm() > 0.0) || !std::isfinite(a.norm())) {
    r.fail(axis_node, ap, "needs a nonzero direction");
  }
  const double angle = r.number(r.required(t, p, "angle"), TomlAccess::join(p, "angle"));
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, a.normalized()));
}

/// One [[body]] table at `p`.
Mechanism::Body read_body(const SceneReader& r, const toml::node& node, const std::string& p,
                          int dim) {
  const auto& t = r.table(node, p);
  r.check_keys(t, p,
               {"name", "mass", "inertia", "position", "angle", "orientation", "velocity",
                "angular_velocity", "points", "axes"});
  Mechanism::Body b;
  b.where = r.at(node, p);
  b.name = r.mechanism_name(r.required(t, p, "name"), TomlAccess::join(p, "name"), "body");
  b.mass = r.positive(r.required(t, p, "mass"), TomlAccess::join(p, "mass"));
  b.inertia = read_inertia(r, r.required(t, p, "inertia"), TomlAccess::join(p, "inertia"), dim);
  b.position =
      r.mechanism_vector(r.required(t, p, "position"), TomlAccess::join(p, "position"), dim);
  if (dim == 2) {
    if (const auto* o = t.get("orientation")) {
      r.fail(*o, TomlAccess::join(p, "orientation"), "a planar body's orientation is its angle");
    }
    if (const auto* a = t.get("angle")) b.angle = r.number(*a, TomlAccess::join(p, "angle"));
    b.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(b.angle, Eigen::Vector3d::UnitZ()));
  } else {
    if (const auto* a = t.get("angle")) {
      r.fail(*a, TomlAccess::join(p, "angle"),
             "a spatial body's orientation is orientation = { quaternion = [w, x, y, z] } or "
             "{ axis = [x, y, z], angle = a }");
    }
    if (const auto* o = t.get("orientation")) {
      b.orientation = read_orientation(r, *o, TomlAccess::join(p, "orientation"));
    }
  }
  if (const auto* v = t.get("velocity")) {
    b.velocity = r.mechanism_vector(*v, TomlAccess::join(p, "velocity"), dim);
  }
  if (const auto* w = t.get("angular_velocity")) {
    const std::string wp = TomlAccess::join(p, "angular_velocity");
    if (dim == 2) {
      if (!w->is_number()) r.fail(*w, wp, "a planar body's angular velocity is one number");
      b.angular_velocity[2] = r.number(*w, wp);
    } else {
      b.angular_velocity = r.mechanism_vector(*w, wp, 3);
    }
  }
  if (const auto* n = t.get("points")) {
    b.points = r.read_markers(*n, TomlAccess::join(p, "points"), dim, false);
  }
  if (const auto* n = t.get("axes")) {
    b.axes = r.read_markers(*n, TomlAccess::join(p, "axes"), dim, true);
  }
  return b;
}

}  // namespace

void SceneReader::read_bodies(const toml::node& node, Mechanism& mechanism) const {
  const auto& arr = array(node, "body");
  std::unordered_map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string p = index("body", i);
    Mechanism::Body b = read_body(*this, *arr.get(i), p, mechanism.dimension);
    const auto& name_node = *arr.get(i)->as_table()->get("name");
    if (b.name == "ground") {
      fail(name_node, join(p, "name"),
           "'ground' is the fixed body's name: give its points in [model] ground");
    }
    if (const auto [at, fresh] = seen.emplace(b.name, i); !fresh) {
      fail(name_node, join(p, "name"),
           "body '" + b.name + "' is already " + index("body", at->second) +
               ": body names must be distinct");
    }
    mechanism.bodies.push_back(std::move(b));
  }
  if (mechanism.bodies.empty()) fail(node, "body", "a multibody model needs at least one body");
}

}  // namespace condyn
