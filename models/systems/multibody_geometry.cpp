#include "models/systems/multibody_geometry.hpp"

#include <cmath>

namespace condyn {

namespace {

Eigen::Vector3d to_vector(const Mechanism::Vec3& x) { return {x[0], x[1], x[2]}; }

}  // namespace

MultibodyGeometry::MultibodyGeometry(const Mechanism& mechanism)
    : dim_(mechanism.dimension), bodies_(static_cast<int>(mechanism.bodies.size())) {}

Eigen::Matrix3d initial_rotation(const Mechanism& m, int body) {
  if (body == Mechanism::kGround) return Eigen::Matrix3d::Identity();
  const auto& b = m.bodies[static_cast<std::size_t>(body)];
  if (m.dimension == 2) return Eigen::AngleAxisd(b.angle, Eigen::Vector3d::UnitZ()).matrix();
  return b.orientation.normalized().toRotationMatrix();
}

AffineVector MultibodyGeometry::point(int body, const Eigen::Vector3d& s) const {
  AffineVector x = direction(body, s);
  if (body == Mechanism::kGround) return x;
  for (int r = 0; r < dim_; ++r)
    x.coefficients[static_cast<std::size_t>(r)][offset(body) + r] += 1.0;
  return x;
}

AffineVector MultibodyGeometry::direction(int body, const Eigen::Vector3d& e) const {
  AffineVector x(dim_);
  if (body == Mechanism::kGround) {
    x.constant = e.head(dim_);
    return x;
  }
  const int o = offset(body);
  if (dim_ == 2) {  // R e = e_x u + e_y perp(u) = (e_x u_x − e_y u_y, e_y u_x + e_x u_y)
    const auto put = [&](int r, int col, double value) {
      if (value != 0.0) x.coefficients[static_cast<std::size_t>(r)][col] = value;
    };
    put(0, o + 2, e[0]);
    put(0, o + 3, -e[1]);
    put(1, o + 2, e[1]);
    put(1, o + 3, e[0]);
    return x;
  }
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      if (e[k] != 0.0) x.coefficients[static_cast<std::size_t>(r)][o + 3 + 3 * k + r] = e[k];
    }
  }
  return x;
}

Eigen::Vector3d MultibodyGeometry::marker(const Mechanism& m, int body, int index) const {
  const auto& list = body == Mechanism::kGround ? m.ground_points
                                                : m.bodies[static_cast<std::size_t>(body)].points;
  return to_vector(list.at(static_cast<std::size_t>(index)).at);
}

Eigen::Vector3d MultibodyGeometry::axis(const Mechanism& m, int body, int index) const {
  const auto& list =
      body == Mechanism::kGround ? m.ground_axes : m.bodies[static_cast<std::size_t>(body)].axes;
  const Eigen::Vector3d e = to_vector(list.at(static_cast<std::size_t>(index)).at);
  return e.normalized();
}

Eigen::Matrix3d MultibodyGeometry::rotation(int body, const ConstRef& q) const {
  if (body == Mechanism::kGround) return Eigen::Matrix3d::Identity();
  const int o = offset(body);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  if (dim_ == 2) {
    R(0, 0) = q[o + 2];
    R(1, 0) = q[o + 3];
    R(0, 1) = -q[o + 3];
    R(1, 1) = q[o + 2];
    return R;
  }
  for (int k = 0; k < 3; ++k) R.col(k) = q.segment(o + 3 + 3 * k, 3);
  return R;
}

Eigen::Vector3d MultibodyGeometry::position(int body, const ConstRef& q) const {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  r.head(dim_) = q.segment(offset(body), dim_);
  return r;
}

MultibodyGeometry::Vector MultibodyGeometry::initial_coordinates(const Mechanism& m) const {
  Vector q = Vector::Zero(coordinates());
  for (int b = 0; b < bodies_; ++b) {
    const auto& body = m.bodies[static_cast<std::size_t>(b)];
    const int o = offset(b);
    for (int r = 0; r < dim_; ++r) q[o + r] = body.position[static_cast<std::size_t>(r)];
    if (dim_ == 2) {
      q[o + 2] = std::cos(body.angle);
      q[o + 3] = std::sin(body.angle);
      continue;
    }
    const Eigen::Matrix3d R = initial_rotation(m, b);
    for (int k = 0; k < 3; ++k) q.segment(o + 3 + 3 * k, 3) = R.col(k);
  }
  return q;
}

MultibodyGeometry::Vector MultibodyGeometry::initial_velocities(const Mechanism& m) const {
  const Vector q = initial_coordinates(m);
  Vector v = Vector::Zero(coordinates());
  for (int b = 0; b < bodies_; ++b) {
    const auto& body = m.bodies[static_cast<std::size_t>(b)];
    const int o = offset(b);
    for (int r = 0; r < dim_; ++r) v[o + r] = body.velocity[static_cast<std::size_t>(r)];
    if (dim_ == 2) {  // u' = ω perp(u)
      const double w = body.angular_velocity[2];
      v[o + 2] = -w * q[o + 3];
      v[o + 3] = w * q[o + 2];
      continue;
    }
    const Eigen::Vector3d w = to_vector(body.angular_velocity);
    for (int k = 0; k < 3; ++k) {  // R_k' = ω × R_k
      const Eigen::Vector3d Rk = q.segment(o + 3 + 3 * k, 3);
      v.segment(o + 3 + 3 * k, 3) = w.cross(Rk);
    }
  }
  return v;
}

}  // namespace condyn
