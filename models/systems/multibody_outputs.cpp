#include "models/systems/multibody_outputs.hpp"

#include <cmath>
#include <numbers>

namespace condyn {

namespace {

/// The columns of a body per quantity: 3 in 2D (x, y, angle), 7 in 3D (x, y, z, qw..qz) for
/// displacement; 3 (2D) or 6 (3D) for the rates.
int pose_columns(int dim) { return dim == 2 ? 3 : 7; }
int rate_columns(int dim) { return dim == 2 ? 3 : 6; }
int wrench_columns(int dim) { return dim == 2 ? 3 : 6; }

std::vector<std::string> suffixed(const std::string& owner, std::initializer_list<const char*> s) {
  std::vector<std::string> out;
  for (const char* x : s) out.push_back(owner + "." + x);
  return out;
}

void append_names(std::vector<std::string>& to, const std::vector<std::string>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

}  // namespace

MultibodyOutputs::MultibodyOutputs(const Mechanism& m, std::shared_ptr<const QuadraticRows> rows,
                                   const std::vector<int>& row_joint)
    : geometry_(m), rows_(std::move(rows)) {
  const bool planar = m.dimension == 2;
  for (const auto& b : m.bodies) {
    start_angles_.push_back(b.angle);
    append_names(displacement_, planar ? suffixed(b.name, {"x", "y", "angle"})
                                       : suffixed(b.name, {"x", "y", "z", "qw", "qx", "qy", "qz"}));
    append_names(velocity_, planar ? suffixed(b.name, {"vx", "vy", "omega"})
                                   : suffixed(b.name, {"vx", "vy", "vz", "wx", "wy", "wz"}));
    append_names(acceleration_,
                 planar ? suffixed(b.name, {"ax", "ay", "alpha"})
                        : suffixed(b.name, {"ax", "ay", "az", "alphax", "alphay", "alphaz"}));
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const auto& joint = m.joints[j];
    append_names(reaction_, planar ? suffixed(joint.name, {"fx", "fy", "m"})
                                   : suffixed(joint.name, {"fx", "fy", "fz", "mx", "my", "mz"}));
    joints_.push_back({joint.bodies[0],
                       joint.bodies[1],
                       geometry_.marker(m, joint.bodies[0], joint.points[0]),
                       geometry_.marker(m, joint.bodies[1], joint.points[1]),
                       {}});
  }
  for (std::size_t i = 0; i < row_joint.size(); ++i) {  // one pass: linear in the rows
    if (row_joint[i] >= 0)
      joints_[static_cast<std::size_t>(row_joint[i])].rows.push_back(static_cast<int>(i));
  }
  for (const auto& p : m.ground_points)
    points_.push_back({"ground." + p.name, Mechanism::kGround, {p.at[0], p.at[1], p.at[2]}});
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    for (const auto& p : m.bodies[b].points) {
      points_.push_back(
          {m.bodies[b].name + "." + p.name, static_cast<int>(b), {p.at[0], p.at[1], p.at[2]}});
    }
  }
}

const std::vector<std::string>& MultibodyOutputs::names(Quantity q) const {
  switch (q) {
    case Quantity::displacement:
      return displacement_;
    case Quantity::velocity:
      return velocity_;
    case Quantity::acceleration:
      return acceleration_;
    case Quantity::reaction:
      return reaction_;
    default:
      return none_;
  }
}

void MultibodyOutputs::displacement(double /*t*/, const Vector& u, const Vector& previous,
                                    Vector& out) const {
  const int dim = geometry_.dimension(), cols = pose_columns(dim);
  const auto bodies = static_cast<int>(start_angles_.size());
  out.resize(static_cast<Eigen::Index>(bodies) * cols);
  const bool first = previous.size() != out.size();
  for (int b = 0; b < bodies; ++b) {
    const int o = geometry_.offset(b), c = b * cols;
    out.segment(c, dim) = u.segment(o, dim);
    if (dim == 2) {
      // The angle nearest the previous one (the scene's at the first row) among atan2 + 2πk.
      const double a = std::atan2(u[o + 3], u[o + 2]);
      const double reference = first ? start_angles_[static_cast<std::size_t>(b)] : previous[c + 2];
      const double turn = 2.0 * std::numbers::pi;
      out[c + 2] = a + turn * std::round((reference - a) / turn);
      continue;
    }
    // Eigen's conversion from a matrix is Shepperd's: the largest of 1 + tr, 1 + 2R_ii − tr
    // decides the branch, so no division by a small number.
    Eigen::Quaterniond quat(geometry_.rotation(b, u));
    quat.normalize();
    Eigen::Vector4d qv(quat.w(), quat.x(), quat.y(), quat.z());
    const bool flip = first ? qv[0] < 0.0 : qv.dot(previous.segment(c + 3, 4)) < 0.0;
    if (flip) qv = -qv;
    out.segment(c + 3, 4) = qv;
  }
}

void MultibodyOutputs::rates(const Vector& u, const Vector& w, Vector& out) const {
  const int dim = geometry_.dimension(), cols = rate_columns(dim);
  const auto bodies = static_cast<int>(start_angles_.size());
  out.resize(static_cast<Eigen::Index>(bodies) * cols);
  for (int b = 0; b < bodies; ++b) {
    const int o = geometry_.offset(b), c = b * cols;
    out.segment(c, dim) = w.segment(o, dim);
    if (dim == 2) {  // u × w_u
      out[c + 2] = u[o + 2] * w[o + 3] - u[o + 3] * w[o + 2];
      continue;
    }
    Eigen::Vector3d axial = Eigen::Vector3d::Zero();  // ½ Σ R_k × w_k
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d Rk = u.segment(o + 3 + 3 * k, 3), wk = w.segment(o + 3 + 3 * k, 3);
      axial += 0.5 * Rk.cross(wk);
    }
    out.segment(c + 3, 3) = axial;
  }
}

void MultibodyOutputs::velocity(double /*t*/, const Vector& u, const Vector& v, Vector& out) const {
  rates(u, v, out);
}

void MultibodyOutputs::acceleration(double /*t*/, const Vector& u, const Vector& /*v*/,
                                    const Vector& a, Vector& out) const {
  // d/dt (u × u') = u × u'' and d/dt ½ Σ R_k × R_k' = ½ Σ R_k × R_k'': the rates' map on a.
  rates(u, a, out);
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> MultibodyOutputs::wrench(int body, const Vector& u,
                                                                     const Vector& Q) const {
  const int o = geometry_.offset(body), dim = geometry_.dimension();
  Eigen::Vector3d F = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  F.head(dim) = Q.segment(o, dim);
  if (dim == 2) {
    torque[2] = u[o + 2] * Q[o + 3] - u[o + 3] * Q[o + 2];
    return {F, torque};
  }
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d Rk = u.segment(o + 3 + 3 * k, 3), Qk = Q.segment(o + 3 + 3 * k, 3);
    torque += Rk.cross(Qk);
  }
  return {F, torque};
}

void MultibodyOutputs::reaction(double t, const Vector& u, const Vector& lambda,
                                Vector& out) const {
  const int dim = geometry_.dimension(), cols = wrench_columns(dim);
  out = Vector::Zero(static_cast<Eigen::Index>(joints_.size()) * cols);
  Vector Q = Vector::Zero(u.size());
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const JointRef& joint = joints_[j];
    for (const int i : joint.rows) rows_->add_gradient(t, t, u, i, -lambda[i], Q);
    // The body the wrench is taken on, the point it is taken about (global), and its sign.
    const bool onto_ground = joint.body2 == Mechanism::kGround;
    const int body = onto_ground ? joint.body1 : joint.body2;
    if (body == Mechanism::kGround) continue;
    const Eigen::Vector3d about = onto_ground
                                      ? joint.point2
                                      : Eigen::Vector3d(geometry_.position(body, u) +
                                                        geometry_.rotation(body, u) * joint.point2);
    auto [F, torque] = wrench(body, u, Q);
    torque += (geometry_.position(body, u) - about).cross(F);
    const double sign = onto_ground ? -1.0 : 1.0;
    const auto c = static_cast<Eigen::Index>(j) * cols;
    out.segment(c, dim) = sign * F.head(dim);
    if (dim == 2) {
      out[c + 2] = sign * torque[2];
    } else {
      out.segment(c + 3, 3) = sign * torque;
    }
    // A joint's rows touch its two bodies' coordinates only: clearing them keeps the map linear
    // in the number of joints (Q.setZero() per joint was quadratic).
    for (const int b : {joint.body1, joint.body2}) {
      if (b != Mechanism::kGround) Q.segment(geometry_.offset(b), geometry_.body_size()).setZero();
    }
  }
}

std::optional<int> MultibodyOutputs::point(std::string_view name) const {
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (points_[i].name == name) return static_cast<int>(i);
  }
  return std::nullopt;
}

void MultibodyOutputs::point_position(int index, const Vector& u, Eigen::Ref<Vector> out) const {
  const Point& p = points_.at(static_cast<std::size_t>(index));
  const int dim = geometry_.dimension();
  if (p.body == Mechanism::kGround) {
    out = p.at.head(dim);
    return;
  }
  out = (geometry_.position(p.body, u) + geometry_.rotation(p.body, u) * p.at).head(dim);
}

}  // namespace condyn
