#include "models/systems/multibody_rows.hpp"

#include <cmath>
#include <stdexcept>

#include "models/core/number_cell.hpp"

namespace condyn {

namespace {

using JointType = Mechanism::JointType;

/// perp(x)·y = x × y (2D).
QuadraticForm cross2(const AffineVector& x, const AffineVector& y) { return dot(x.perp(), y); }

QuadraticForm plus_constant(QuadraticForm form, double c) {
  form.c += c;
  return form;
}

/// A unit vector orthogonal to a (unit): the coordinate axis least aligned with a, made
/// orthogonal to it.
Eigen::Vector3d orthogonal_to(const Eigen::Vector3d& a) {
  Eigen::Index k = 0;
  a.cwiseAbs().minCoeff(&k);
  const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
  return (e - e.dot(a) * a).normalized();
}

/// What one joint's rows are built from (see multibody_rows.hpp).
class JointFrame {
 public:
  JointFrame(const Mechanism& m, const MultibodyGeometry& g, const Eigen::VectorXd& q0, int j)
      : m_(m), g_(g), q0_(q0), joint_(m.joints[static_cast<std::size_t>(j)]) {
    const int b1 = joint_.bodies[0], b2 = joint_.bodies[1];
    p1 = g.point(b1, g.marker(m, b1, joint_.points[0]));
    p2 = g.point(b2, g.marker(m, b2, joint_.points[1]));
    d = p2 - p1;
    const bool planar = m.dimension == 2;
    a1_body_ = joint_.axes[0] >= 0
                   ? g.axis(m, b1, joint_.axes[0])
                   : Eigen::Vector3d(planar ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ());
    const Eigen::Vector3d b1_body = planar ? Eigen::Vector3d::UnitX() : orthogonal_to(a1_body_);
    const Eigen::Vector3d c1_body = planar ? Eigen::Vector3d::UnitY() : a1_body_.cross(b1_body);
    a1 = g.direction(b1, a1_body_);
    b1v = g.direction(b1, b1_body);
    c1 = g.direction(b1, c1_body);
    a2 = joint_.axes[1] >= 0 ? g.direction(b2, g.axis(m, b2, joint_.axes[1])) : follower(a1_body_);
    e2 = follower(b1_body);
  }

  /// The body-2-fixed vector equal to body 1's vector e (body frame) at t = 0.
  [[nodiscard]] AffineVector follower(const Eigen::Vector3d& e) const {
    const Eigen::Matrix3d R1 = initial_rotation(m_, joint_.bodies[0]);
    const Eigen::Matrix3d R2 = initial_rotation(m_, joint_.bodies[1]);
    return g_.direction(joint_.bodies[1], R2.transpose() * (R1 * e));
  }

  /// d·a1 at t = 0: the slide a prismatic drive counts from.
  [[nodiscard]] double initial_slide() const { return dot(d, a1).value(q0_); }
  /// The distance joint's length: `length`, or |d| at t = 0.
  [[nodiscard]] double length() const {
    if (joint_.length) return *joint_.length;
    return d.value(q0_).norm();
  }

  AffineVector p1, p2, d, a1, b1v, c1, a2, e2;

 private:
  const Mechanism& m_;
  const MultibodyGeometry& g_;
  const Eigen::VectorXd& q0_;
  const Mechanism::Joint& joint_;
  Eigen::Vector3d a1_body_;
};

/// Appends rows to a set, naming them after a joint or a body.
class MultibodyRowWriter {
 public:
  MultibodyRowWriter(MultibodyRowSet& set, std::string owner, int joint, SourcePoint where)
      : set_(set), owner_(std::move(owner)), joint_(joint), where_(std::move(where)) {}

  void add(const std::string& what, const std::string& kind, QuadraticForm form) {
    add_terms(what, kind, {{TimeFactor::one, -1, std::move(form)}});
  }
  void add_terms(const std::string& what, const std::string& kind,
                 std::vector<QuadraticTerm> terms) {
    set_.rows.push_back({owner_ + "." + what, kind, std::move(terms), joint_, where_});
  }
  /// d = 0, one row per direction.
  void coincide(const AffineVector& d, const std::string& says) {
    static const char* const axes[] = {"x", "y", "z"};
    for (int r = 0; r < d.dim(); ++r) add(axes[r], says + ", " + axes[r], d.entry(r));
  }

 private:
  MultibodyRowSet& set_;
  std::string owner_;
  int joint_;
  SourcePoint where_;
};

void add_rigid_rows(const Mechanism& m, const MultibodyGeometry& g, MultibodyRowSet& set) {
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const auto& body = m.bodies[b];
    MultibodyRowWriter out(set, body.name, -1, body.where);
    const int k = static_cast<int>(b);
    if (m.dimension == 2) {
      const AffineVector u = g.direction(k, Eigen::Vector3d::UnitX());
      out.add(std::string(kRigidRow), "unit x axis of " + body.name + ": (|u|^2 - 1)/2 = 0",
              plus_constant(dot(u, u).scaled(0.5), -0.5));
      continue;
    }
    static const char* const names[] = {"x", "y", "z"};
    std::vector<AffineVector> R;
    R.reserve(3);
    for (int c = 0; c < 3; ++c) R.push_back(g.direction(k, Eigen::Vector3d::Unit(c)));
    for (int c = 0; c < 3; ++c) {
      const std::string n = names[c];
      out.add(std::string(kRigidRow) + "_" + n + n,
              "unit column " + n + " of " + body.name + "'s rotation: (|R_" + n + "|^2 - 1)/2 = 0",
              plus_constant(
                  dot(R[static_cast<std::size_t>(c)], R[static_cast<std::size_t>(c)]).scaled(0.5),
                  -0.5));
    }
    for (const auto& [i, j] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
      const std::string a = names[i], c = names[j];
      out.add(std::string(kRigidRow) + "_" + a + c,
              "orthogonal columns of " + body.name + "'s rotation: R_" + a + ".R_" + c + " = 0",
              dot(R[static_cast<std::size_t>(i)], R[static_cast<std::size_t>(j)]));
    }
  }
}

/// The drive rows of a revolute or prismatic joint (drive index `k`).
void add_drive(const Mechanism::Joint& joint, const JointFrame& f, int k, MultibodyRowWriter& out) {
  if (joint.type == JointType::revolute) {
    out.add_terms("drive",
                  "relative angle of " + std::string("the revolute joint = drive(t): (e2.c1) cos "
                                                     "theta(t) - (e2.b1) sin theta(t) = 0"),
                  {{TimeFactor::cos_drive, k, dot(f.e2, f.c1)},
                   {TimeFactor::sin_drive, k, dot(f.e2, f.b1v).scaled(-1.0)}});
    return;
  }
  QuadraticForm minus_one;
  minus_one.c = -1.0;
  out.add_terms("drive", "slide of the prismatic joint = drive(t): (p2 - p1).a1 - s0 - s(t) = 0",
                {{TimeFactor::one, -1, plus_constant(dot(f.d, f.a1), -f.initial_slide())},
                 {TimeFactor::drive, k, minus_one}});
}

void add_distance(const JointFrame& f, const std::string& at, MultibodyRowWriter& out) {
  const double L = f.length();
  if (!(L > 0.0)) throw std::invalid_argument("a distance joint of length 0 (" + at + ")");
  out.add("distance", "distance |p2 - p1| = " + shortest_number(L) + " (" + at + ")",
          plus_constant(dot(f.d, f.d).scaled(0.5 / L), -0.5 * L));
}

void add_planar_joint(const Mechanism::Joint& joint, const JointFrame& f, const std::string& at,
                      MultibodyRowWriter& out) {
  switch (joint.type) {
    case JointType::revolute:
      out.coincide(f.d, at);
      return;
    case JointType::prismatic:
      out.add("angle", "axes parallel: a1 x a2 = 0 (" + at + ")", cross2(f.a1, f.a2));
      out.add("offset", "on the axis: a1 x (p2 - p1) = 0 (" + at + ")", cross2(f.a1, f.d));
      return;
    case JointType::fixed:
      out.coincide(f.d, at);
      out.add("rotation", "no relative rotation: u1 x e2 = 0 (" + at + ")", cross2(f.b1v, f.e2));
      return;
    case JointType::distance:
      add_distance(f, at, out);
      return;
    case JointType::point_on_line:
      out.add("offset", "on the line: a1 x (p2 - p1) = 0 (" + at + ")", cross2(f.a1, f.d));
      return;
    default:
      throw std::invalid_argument(std::string("a ") + to_string(joint.type) +
                                  " joint in a planar mechanism (" + at + ")");
  }
}

void add_spatial_axis(const JointFrame& f, const std::string& at, MultibodyRowWriter& out) {
  out.add("axis_b", "axes aligned: a2.b1 = 0 (" + at + ")", dot(f.a2, f.b1v));
  out.add("axis_c", "axes aligned: a2.c1 = 0 (" + at + ")", dot(f.a2, f.c1));
}

void add_spatial_line(const JointFrame& f, const std::string& at, MultibodyRowWriter& out) {
  out.add("offset_b", "on the axis: (p2 - p1).b1 = 0 (" + at + ")", dot(f.d, f.b1v));
  out.add("offset_c", "on the axis: (p2 - p1).c1 = 0 (" + at + ")", dot(f.d, f.c1));
}

void add_spatial_joint(const Mechanism::Joint& joint, const JointFrame& f, const std::string& at,
                       MultibodyRowWriter& out) {
  const JointType type = joint.type;
  if (type == JointType::spherical || type == JointType::revolute || type == JointType::universal ||
      type == JointType::fixed) {
    out.coincide(f.d, at);
  }
  switch (type) {
    case JointType::revolute:
      add_spatial_axis(f, at, out);
      return;
    case JointType::cylindrical:
    case JointType::prismatic:
      add_spatial_axis(f, at, out);
      add_spatial_line(f, at, out);
      if (type == JointType::prismatic)
        out.add("twist", "no rotation about the axis: e2.c1 = 0 (" + at + ")", dot(f.e2, f.c1));
      return;
    case JointType::universal:
      out.add("cross", "axes orthogonal: a1.a2 = 0 (" + at + ")", dot(f.a1, f.a2));
      return;
    case JointType::point_on_line:
      add_spatial_line(f, at, out);
      return;
    case JointType::point_on_plane:
      out.add("normal", "in the plane: (p2 - p1).a1 = 0 (" + at + ")", dot(f.d, f.a1));
      return;
    case JointType::distance:
      add_distance(f, at, out);
      return;
    default:
      return;  // spherical: the points alone; fixed: below
  }
}

/// The 3D fixed joint's orientation rows: body 2's copies of body 1's frame stay body 1's.
void add_spatial_lock(const MultibodyGeometry& g, int b1, const JointFrame& f,
                      const std::string& at, MultibodyRowWriter& out) {
  const AffineVector x1 = g.direction(b1, Eigen::Vector3d::UnitX());
  const AffineVector y1 = g.direction(b1, Eigen::Vector3d::UnitY());
  const AffineVector z1 = g.direction(b1, Eigen::Vector3d::UnitZ());
  const AffineVector x2 = f.follower(Eigen::Vector3d::UnitX());
  const AffineVector y2 = f.follower(Eigen::Vector3d::UnitY());
  out.add("rot_z", "no relative rotation about z: e2x.y1 = 0 (" + at + ")", dot(x2, y1));
  out.add("rot_y", "no relative rotation about y: e2x.z1 = 0 (" + at + ")", dot(x2, z1));
  out.add("rot_x", "no relative rotation about x: e2y.z1 = 0 (" + at + ")", dot(y2, z1));
}

std::string body_name(const Mechanism& m, int b) {
  return b == Mechanism::kGround ? "ground" : m.bodies[static_cast<std::size_t>(b)].name;
}

std::string point_name(const Mechanism& m, int b, int p) {
  const auto& list =
      b == Mechanism::kGround ? m.ground_points : m.bodies[static_cast<std::size_t>(b)].points;
  return list.at(static_cast<std::size_t>(p)).name;
}

void add_joint_rows(const Mechanism& m, const MultibodyGeometry& g, const Eigen::VectorXd& q0,
                    int j, MultibodyRowSet& set) {
  const auto& joint = m.joints[static_cast<std::size_t>(j)];
  const JointFrame f(m, g, q0, j);
  const std::string at = std::string(to_string(joint.type)) + " joint: point " +
                         point_name(m, joint.bodies[1], joint.points[1]) + " of " +
                         body_name(m, joint.bodies[1]) + " at point " +
                         point_name(m, joint.bodies[0], joint.points[0]) + " of " +
                         body_name(m, joint.bodies[0]);
  MultibodyRowWriter out(set, joint.name, j, joint.where);
  if (m.dimension == 2) {
    add_planar_joint(joint, f, at, out);
  } else {
    add_spatial_joint(joint, f, at, out);
    if (joint.type == JointType::fixed) add_spatial_lock(g, joint.bodies[0], f, at, out);
  }
  if (!joint.drive) return;
  if (joint.type != JointType::revolute && joint.type != JointType::prismatic) {
    throw std::invalid_argument("joint '" + joint.name + "': a drive on a " +
                                to_string(joint.type) + " joint, which has no coordinate");
  }
  set.drives.push_back(*joint.drive);
  add_drive(joint, f, static_cast<int>(set.drives.size()) - 1, out);
}

}  // namespace

MultibodyRowSet multibody_rows(const Mechanism& m, const MultibodyGeometry& g) {
  MultibodyRowSet set;
  add_rigid_rows(m, g, set);
  const Eigen::VectorXd q0 = g.initial_coordinates(m);
  for (std::size_t j = 0; j < m.joints.size(); ++j)
    add_joint_rows(m, g, q0, static_cast<int>(j), set);
  return set;
}

RelativeAngle relative_angle(const Mechanism& m, const MultibodyGeometry& g,
                             const Eigen::VectorXd& q0, int joint) {
  const JointFrame f(m, g, q0, joint);
  return {dot(f.e2, f.b1v), dot(f.e2, f.c1)};
}

}  // namespace condyn
