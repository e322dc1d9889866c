// Mechanisms of rigid bodies in natural coordinates (models/systems/multibody_system.hpp): every
// derivative of every joint type, drive and force element against central differences, the mass
// matrix's kinetic energy, markers, the output map's columns and the reactions of a pendulum.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanism.hpp"
#include "models/systems/multibody_system.hpp"
#include "tests/system_check.hpp"

using namespace condyn;

namespace test_multibody_system {

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Roundoff of a few dozen operations on O(1) values (rotations, products of unit vectors).
constexpr double kRoundoff = 64 * kEps;
constexpr double kGravity = 9.81;

using JointType = Mechanism::JointType;
using ForceType = Mechanism::ForceType;

TimeFunction harmonic(double amplitude, double omega, double phase) {
  TimeTerm t;
  t.kind = TimeTerm::Kind::harmonic;
  t.amplitude = amplitude;
  t.omega = omega;
  t.phase = phase;
  return TimeFunction({t});
}

/// 0.3 t + 0.2 t² − 0.1 t³: 0 at t = 0, nonzero first and second derivatives.
TimeFunction polynomial_drive() {
  TimeTerm t;
  t.kind = TimeTerm::Kind::polynomial;
  t.coefficients = {0.0, 0.3, 0.2, -0.1};
  return TimeFunction({t});
}

Mechanism::Body body(const std::string& name, int dim, const Mechanism::Vec3& position,
                     double angle, const Eigen::Vector3d& axis) {
  Mechanism::Body b;
  b.name = name;
  b.mass = 1.3;
  b.inertia << 0.4, 0.05, -0.02, 0.05, 0.3, 0.03, -0.02, 0.03, 0.5;
  if (dim == 2) b.inertia = Eigen::Matrix3d::Identity() * 0.2;
  b.position = position;
  b.angle = angle;
  b.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
  if (dim == 2)
    b.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
  b.velocity = {0.2, -0.1, dim == 3 ? 0.3 : 0.0};
  b.angular_velocity = {dim == 3 ? 0.4 : 0.0, dim == 3 ? -0.2 : 0.0, 0.7};
  b.points = {{"P", {-0.5, 0.1, dim == 3 ? 0.2 : 0.0}}, {"Q", {0.5, -0.05, 0.0}}};
  b.axes = {{"ax", {1.0, 0.0, 0.0}}, {"az", {0.0, 0.0, 1.0}}};
  if (dim == 2) b.axes = {{"ax", {0.6, 0.8, 0.0}}};
  return b;
}

/// Ground – a by a revolute (3D: about z) or the given first joint; a – b by `type`, optionally
/// driven; gravity, a spring-damper, a rotational spring-damper at the first joint, a point
/// force on b and a torque on a.
Mechanism two_bodies(int dim, JointType type, bool driven, bool b_to_ground = false) {
  Mechanism m;
  m.dimension = dim;
  m.gravity = {0.0, -kGravity, 0.0};
  m.ground_points = {{"O", {0.0, 0.0, 0.0}}, {"G", {1.0, 0.5, dim == 3 ? 0.2 : 0.0}}};
  m.ground_axes = {{"n", {0.0, 0.0, 1.0}}};
  if (dim == 2) m.ground_axes = {{"n", {1.0, 0.0, 0.0}}};
  m.bodies.push_back(body("a", dim, {0.5, -0.1, 0.0}, 0.3, {0.2, 0.3, 1.0}));
  m.bodies.push_back(body("b", dim, {1.2, 0.2, dim == 3 ? 0.1 : 0.0}, -0.4, {1.0, -0.5, 0.3}));
  Mechanism::Joint hinge;
  hinge.name = "hinge";
  hinge.type = JointType::revolute;
  hinge.bodies = {Mechanism::kGround, 0};
  hinge.points = {0, 0};
  if (dim == 3) hinge.axes = {0, 1};
  m.joints.push_back(hinge);
  Mechanism::Joint j;
  j.name = "tested";
  j.type = type;
  j.bodies = {0, b_to_ground ? Mechanism::kGround : 1};
  j.points = {1, b_to_ground ? 1 : 0};
  j.axes = {0, 0};
  if (type == JointType::universal && !b_to_ground) j.axes = {0, 1};  // ax ⊥ az
  if (type == JointType::distance) j.length = 0.9;
  if (driven) j.drive = type == JointType::revolute ? harmonic(0.4, 1.7, 0.0) : polynomial_drive();
  m.joints.push_back(j);
  Mechanism::Force spring;
  spring.type = ForceType::spring_damper;
  spring.bodies = {0, Mechanism::kGround};
  spring.points = {1, 1};
  spring.k = 30.0;
  spring.c = 0.7;
  spring.rest_length = 0.4;
  Mechanism::Force rot;
  rot.type = ForceType::rotational_spring_damper;
  rot.joint = 0;
  rot.k = 5.0;
  rot.c = 0.3;
  rot.rest_angle = 0.25;
  Mechanism::Force push;
  push.type = ForceType::point_force;
  push.bodies = {b_to_ground ? 0 : 1, Mechanism::kGround};
  push.points = {1, 0};
  for (int r = 0; r < dim; ++r) push.components.push_back(harmonic(1.0 + r, 2.0, 0.3 * r));
  Mechanism::Force twist;
  twist.type = ForceType::torque;
  twist.bodies = {0, Mechanism::kGround};
  for (int r = 0; r < (dim == 2 ? 1 : 3); ++r)
    twist.components.push_back(harmonic(0.5 + r, 1.3, 0.2 + r));
  m.forces = {spring, rot, push, twist};
  return m;
}

/// q0 perturbed off the manifold, generic rates, accelerations and multipliers.
struct State {
  Eigen::VectorXd u, v, a, w;
};
State generic_state(const MultibodyParts& p) {
  const auto n = p.q0.size();
  const int m = p.system->constraints();
  return {p.q0 + 0.05 * Eigen::VectorXd::LinSpaced(n, -1.0, 1.3),
          Eigen::VectorXd::LinSpaced(n, 0.7, -0.4), Eigen::VectorXd::LinSpaced(n, -1.1, 0.9),
          Eigen::VectorXd::LinSpaced(m, 0.8, -1.7)};
}

void check_derivatives(const Mechanism& m) {
  const MultibodyParts p = build_multibody(m);
  const State s = generic_state(p);
  const auto problems = test::check_system_derivatives(*p.system, 0.37, s.u, s.v, s.a, s.w);
  for (const auto& message : problems) FAIL_CHECK(message);
  CHECK(problems.empty());
  // At q = 0, where the formulations take their patterns, no frame exists (u = 0, R = 0): the
  // forces' tangents are still finite (the rotational spring's angle is undefined there).
  auto evaluator = p.system->clone();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(p.q0.size());
  CHECK(Eigen::MatrixXd(evaluator->stiffness(0.0, zero, zero)).allFinite());
  CHECK(Eigen::MatrixXd(evaluator->damping(0.0, zero, zero)).allFinite());
}

/// ½ m |v|² + ½ ωᵀ (R I Rᵀ) ω: the rigid body's kinetic energy, ω global.
double rigid_kinetic_energy(const Mechanism::Body& b, const Eigen::Matrix3d& R) {
  const Eigen::Vector3d v(b.velocity[0], b.velocity[1], b.velocity[2]);
  const Eigen::Vector3d w(b.angular_velocity[0], b.angular_velocity[1], b.angular_velocity[2]);
  return 0.5 * b.mass * v.squaredNorm() + 0.5 * w.dot(R * b.inertia * R.transpose() * w);
}

/// The consistent multipliers of a state: [M Aᵀ; A 0] [a; λ] = [f; γ].
Eigen::VectorXd multipliers(const MultibodyParts& p, double t, const Eigen::VectorXd& q,
                            const Eigen::VectorXd& v) {
  auto s = p.system->clone();
  const int n = s->dofs(), m = s->constraints();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  const Eigen::MatrixXd A(s->constraint_jacobian(t, q));
  K.topLeftCorner(n, n) = Eigen::MatrixXd(s->mass(t, q));
  K.topRightCorner(n, m) = A.transpose();
  K.bottomLeftCorner(m, n) = A;
  Eigen::VectorXd rhs(n + m);
  Eigen::VectorXd f(n), gamma(m);
  s->force(t, q, v, f);
  s->acceleration_bias(t, q, v, gamma);
  rhs << f, gamma;
  return K.fullPivLu().solve(rhs).tail(m);
}

}  // namespace

TEST_CASE("multibody: every joint's rows and every force agree with central differences") {
  for (int dim : {2, 3}) {
    std::vector<JointType> types = {JointType::revolute, JointType::prismatic, JointType::fixed,
                                    JointType::distance, JointType::point_on_line};
    if (dim == 3) {
      types.insert(types.end(), {JointType::spherical, JointType::universal, JointType::cylindrical,
                                 JointType::point_on_plane});
    }
    for (const JointType type : types) {
      const bool drivable = type == JointType::revolute || type == JointType::prismatic;
      for (const bool driven : {false, true}) {
        if (driven && !drivable) continue;
        for (const bool to_ground : {false, true}) {
          CAPTURE(dim);
          CAPTURE(std::string(to_string(type)));
          CAPTURE(driven);
          CAPTURE(to_ground);
          check_derivatives(two_bodies(dim, type, driven, to_ground));
        }
      }
    }
  }
}

TEST_CASE("multibody: rows named per joint, drives rheonomic, point rows linear") {
  const MultibodyParts p = build_multibody(two_bodies(2, JointType::revolute, true));
  // 2 rigid rows, the hinge's 2, the tested joint's 2 and its drive.
  REQUIRE(p.rows.size() == 7);
  CHECK(p.rows[0].name == "a.rigid");
  CHECK(p.rows[2].name == "hinge.x");
  CHECK(p.rows[6].name == "tested.drive");
  CHECK(p.row_rheonomic == std::vector<bool>{false, false, false, false, false, false, true});
  CHECK(p.row_joint == std::vector<int>{-1, -1, 0, 0, 1, 1, 1});
  CHECK_FALSE(p.rows[2].coefficients.empty());  // r + R s − O: linear, constant coefficients
  CHECK(p.rows[0].coefficients.empty());
  CHECK(p.coordinate_names[2] == "a.ux");
  // What a row says, with its figures as written.
  const MultibodyParts pd = build_multibody(two_bodies(2, JointType::distance, false));
  CHECK(pd.rows[4].name == "tested.distance");
  CHECK(pd.rows[4].nonlinear_kind.find(
            "|p2 - p1| = 0.9 (distance joint: point P of b at point Q of a)") != std::string::npos);
  const MultibodyParts p3 = build_multibody(two_bodies(3, JointType::revolute, false));
  CHECK(p3.coordinate_names[4] == "a.R21");  // row 2 of column 1
  CHECK(p3.rows[3].name == "a.rigid_xy");
}

TEST_CASE("multibody: the mass matrix gives the rigid body's kinetic energy") {
  std::srand(7);  // Eigen's Random: a fixed sequence of motions
  for (int dim : {2, 3}) {
    for (int trial = 0; trial < 5; ++trial) {
      Mechanism m = two_bodies(dim, JointType::revolute, false);
      for (auto& b : m.bodies) {
        const Eigen::Vector3d v = Eigen::Vector3d::Random(), w = Eigen::Vector3d::Random();
        b.velocity = {v[0], v[1], dim == 3 ? v[2] : 0.0};
        b.angular_velocity = {dim == 3 ? w[0] : 0.0, dim == 3 ? w[1] : 0.0, w[2]};
        b.angle = 3.0 * w[0];
        b.orientation =
            dim == 3 ? Eigen::Quaterniond::UnitRandom()
                     : Eigen::Quaterniond(Eigen::AngleAxisd(b.angle, Eigen::Vector3d::UnitZ()));
      }
      const MultibodyParts p = build_multibody(m);
      auto s = p.system->clone();
      const double T = 0.5 * p.v0.dot(s->mass(0.0, p.q0) * p.v0);
      double expected = 0.0;
      for (const auto& b : m.bodies)
        expected += rigid_kinetic_energy(b, b.orientation.toRotationMatrix());
      CAPTURE(dim);
      CAPTURE(trial);
      // Roundoff of O(1) energies summed over two bodies.
      CHECK(std::abs(T - expected) < kRoundoff * expected);
    }
  }
}

TEST_CASE("multibody: a marker is at r + R s, and the reactions' point is the joint's") {
  const Mechanism m = two_bodies(3, JointType::spherical, false);
  const MultibodyParts p = build_multibody(m);
  const auto index = p.outputs->point("b.P");
  REQUIRE(index);
  Eigen::VectorXd x(3);
  p.outputs->point_position(*index, p.q0, x);
  const auto& b = m.bodies[1];
  const Eigen::Vector3d expected = Eigen::Vector3d(b.position[0], b.position[1], b.position[2]) +
                                   b.orientation * Eigen::Vector3d(-0.5, 0.1, 0.2);
  CHECK((x - expected).norm() < kRoundoff);
  REQUIRE(p.outputs->point("ground.G"));
  p.outputs->point_position(*p.outputs->point("ground.G"), p.q0, x);
  CHECK(x == Eigen::Vector3d(1.0, 0.5, 0.2));
  CHECK_FALSE(p.outputs->point("b.nothing"));
}

TEST_CASE("multibody outputs: a known pose and angular velocity give back their columns") {
  const Mechanism m = two_bodies(3, JointType::spherical, false);
  const MultibodyParts p = build_multibody(m);
  Eigen::VectorXd pose, rates;
  p.outputs->displacement(0.0, p.q0, Eigen::VectorXd(), pose);
  p.outputs->velocity(0.0, p.q0, p.v0, rates);
  REQUIRE(p.outputs->names(Quantity::displacement).size() == 14);
  CHECK(p.outputs->names(Quantity::displacement)[3] == "a.qw");
  CHECK(p.outputs->names(Quantity::velocity)[3] == "a.wx");
  CHECK(p.outputs->names(Quantity::reaction)[11] == "tested.mz");
  for (std::size_t b = 0; b < 2; ++b) {
    const auto& body = m.bodies[b];
    const auto c = static_cast<Eigen::Index>(7 * b), r = static_cast<Eigen::Index>(6 * b);
    const Eigen::Quaterniond q = body.orientation;
    const Eigen::Vector4d expected =
        (q.w() < 0 ? -1.0 : 1.0) * Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    CHECK((pose.segment(c + 3, 4) - expected).norm() < kRoundoff);
    CHECK(pose[c + 3] > 0.0);
    for (int k = 0; k < 3; ++k) {
      CHECK(std::abs(pose[c + k] - body.position[static_cast<std::size_t>(k)]) < kRoundoff);
      CHECK(std::abs(rates[r + k] - body.velocity[static_cast<std::size_t>(k)]) < kRoundoff);
      CHECK(std::abs(rates[r + 3 + k] - body.angular_velocity[static_cast<std::size_t>(k)]) <
            kRoundoff);
    }
  }
  // The sign follows the previous row: given −q before, −q now.
  Eigen::VectorXd previous = pose, again;
  previous.segment(3, 4) *= -1.0;
  p.outputs->displacement(0.1, p.q0, previous, again);
  CHECK((again.segment(3, 4) + pose.segment(3, 4)).norm() < kRoundoff);
  CHECK((again.segment(10, 4) - pose.segment(10, 4)).norm() < kRoundoff);
}

TEST_CASE("multibody outputs: the planar angle continues across ±π") {
  Mechanism m = two_bodies(2, JointType::revolute, false);
  m.bodies[0].angle = 3.0 + 2.0 * std::numbers::pi;  // the scene's angle, a turn beyond
  const MultibodyParts p = build_multibody(m);
  Eigen::VectorXd pose;
  p.outputs->displacement(0.0, p.q0, Eigen::VectorXd(), pose);
  CHECK(std::abs(pose[2] - m.bodies[0].angle) < kRoundoff * 10.0);  // atan2 of a value near 9.3
  // Rotate body a to 3.5 rad, past π: atan2 says 3.5 − 2π, the continued angle 3.5 + 2π.
  Eigen::VectorXd q = p.q0;
  q[2] = std::cos(3.5);
  q[3] = std::sin(3.5);
  Eigen::VectorXd next;
  p.outputs->displacement(0.1, q, pose, next);
  CHECK(std::abs(next[2] - (3.5 + 2.0 * std::numbers::pi)) < kRoundoff * 10.0);
  // ω = u × u' for u' = ω perp(u).
  Eigen::VectorXd rates;
  p.outputs->velocity(0.0, p.q0, p.v0, rates);
  CHECK(std::abs(rates[2] - 0.7) < kRoundoff);
}

TEST_CASE("multibody: a torque's generalized force has moment T (3D: ½ T × R_k)") {
  Mechanism m = two_bodies(3, JointType::spherical, false);
  m.gravity = {0.0, 0.0, 0.0};
  m.forces = {m.forces[3]};  // the torque on a alone
  const MultibodyParts p = build_multibody(m);
  auto s = p.system->clone();
  const double t = 0.8;
  Eigen::VectorXd f(p.q0.size());
  s->force(t, p.q0, p.v0, f);
  Eigen::Vector3d moment = Eigen::Vector3d::Zero(), T;
  for (int k = 0; k < 3; ++k) {
    moment +=
        Eigen::Vector3d(p.q0.segment(3 + 3 * k, 3)).cross(Eigen::Vector3d(f.segment(3 + 3 * k, 3)));
    T[k] = m.forces[0].components[static_cast<std::size_t>(k)].value(t);
  }
  CHECK((moment - T).norm() < kRoundoff * T.norm());
  CHECK(f.head(3).norm() == 0.0);
}

TEST_CASE("multibody: the springs' force is minus the gradient of their potential") {
  for (int dim : {2, 3}) {
    Mechanism m = two_bodies(dim, JointType::revolute, false);
    for (auto& f : m.forces) f.c = 0.0;
    m.forces.resize(2);  // the spring and the rotational spring: conservative with gravity
    const MultibodyParts p = build_multibody(m);
    auto s = p.system->clone();
    const State st = generic_state(p);
    Eigen::VectorXd f(st.u.size()), zero = Eigen::VectorXd::Zero(st.u.size());
    s->force(0.0, st.u, zero, f);
    REQUIRE(s->energy(0.0, st.u, zero));
    for (Eigen::Index j = 0; j < st.u.size(); ++j) {
      const double h = 1e-6;
      Eigen::VectorXd up = st.u, um = st.u;
      up[j] += h;
      um[j] -= h;
      const double dV =
          (s->energy_parts(0.0, up, zero)->potential - s->energy_parts(0.0, um, zero)->potential) /
          (2 * h);
      CAPTURE(dim);
      CAPTURE(j);
      // Central difference of O(10) potentials at h = 1e-6: truncation h² |V'''| and roundoff
      // eps |V| / h, both below 1e-8 of the forces' size (about 30 N).
      CHECK(std::abs(f[j] + dV) < 1e-7 * 30.0);
    }
  }
}

TEST_CASE("multibody reactions: a hanging pendulum's hinge carries m g, and a held one m g l") {
  for (int dim : {2, 3}) {
    Mechanism m;
    m.dimension = dim;
    m.gravity = {0.0, -kGravity, 0.0};
    m.ground_points = {{"O", {0.0, 0.0, 0.0}}};
    m.bodies.push_back(body("bob", dim, {0.0, -0.7, 0.0}, 0.0, Eigen::Vector3d::UnitZ()));
    m.bodies[0].velocity = {};
    m.bodies[0].angular_velocity = {};
    m.bodies[0].points = {{"top", {0.0, 0.7, 0.0}}};
    Mechanism::Joint hinge;
    hinge.name = "hinge";
    hinge.type = dim == 2 ? JointType::revolute : JointType::spherical;
    hinge.bodies = {Mechanism::kGround, 0};
    m.joints.push_back(hinge);
    const MultibodyParts p = build_multibody(m);
    Eigen::VectorXd out;
    p.outputs->reaction(0.0, p.q0, multipliers(p, 0.0, p.q0, p.v0), out);
    CAPTURE(dim);
    const double mg = m.bodies[0].mass * kGravity;
    // The joint holds the weight: F = m g up, no moment about the hinge (roundoff of m g).
    CHECK(std::abs(out[0]) < kRoundoff * mg);
    CHECK(std::abs(out[1] - mg) < kRoundoff * mg);
    for (Eigen::Index k = dim; k < out.size(); ++k) CHECK(std::abs(out[k]) < kRoundoff * mg);
  }
  // A planar bar held horizontal by a driven hinge (drive 0): the drive's torque m g l holds it.
  Mechanism m;
  m.dimension = 2;
  m.gravity = {0.0, -kGravity, 0.0};
  m.ground_points = {{"O", {0.0, 0.0, 0.0}}};
  m.bodies.push_back(body("bar", 2, {0.6, 0.0, 0.0}, 0.0, Eigen::Vector3d::UnitZ()));
  m.bodies[0].velocity = {};
  m.bodies[0].angular_velocity = {};
  m.bodies[0].points = {{"end", {-0.6, 0.0, 0.0}}};
  Mechanism::Joint hinge;
  hinge.name = "motor";
  hinge.bodies = {Mechanism::kGround, 0};
  TimeTerm zero;
  zero.coefficients = {0.0};
  hinge.drive = TimeFunction({zero});
  m.joints.push_back(hinge);
  const MultibodyParts p = build_multibody(m);
  Eigen::VectorXd out;
  p.outputs->reaction(0.0, p.q0, multipliers(p, 0.0, p.q0, p.v0), out);
  const double mg = m.bodies[0].mass * kGravity;
  CHECK(std::abs(out[0]) < kRoundoff * mg);
  CHECK(std::abs(out[1] - mg) < kRoundoff * mg);
  CHECK(std::abs(out[2] - mg * 0.6) < kRoundoff * mg);
}

namespace {

/// Body b placed so that the tested joint holds at t = 0: b turned about a's axis `ax` by psi
/// (0 where the joint locks the rotation), its point P at a's point Q moved by `shift` (along
/// the axis where the joint lets it slide, across it for point_on_plane and distance).
Mechanism assembled(int dim, JointType type) {
  Mechanism m = two_bodies(dim, type, false);
  m.joints[1].length.reset();  // a distance joint: the distance at t = 0
  auto& a = m.bodies[0];
  auto& b = m.bodies[1];
  const Eigen::Matrix3d Ra = a.orientation.toRotationMatrix();
  const Eigen::Vector3d axis =
      Ra * Eigen::Vector3d(a.axes[0].at[0], a.axes[0].at[1], a.axes[0].at[2]);
  const bool locked = type == JointType::prismatic || type == JointType::fixed;
  const double psi = locked ? 0.0 : 0.3;
  const Eigen::Vector3d turn_axis = dim == 2 ? Eigen::Vector3d::UnitZ() : axis;
  const Eigen::Matrix3d Rb = Eigen::AngleAxisd(psi, turn_axis).matrix() * Ra;
  b.orientation = Eigen::Quaterniond(Rb);
  b.angle = a.angle + psi;
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  if (type == JointType::prismatic || type == JointType::cylindrical ||
      type == JointType::point_on_line)
    shift = 0.35 * axis;
  if (type == JointType::point_on_plane || type == JointType::distance)
    shift = 0.35 * (dim == 2 ? Eigen::Vector3d(-axis[1], axis[0], 0.0) : axis.unitOrthogonal());
  const Eigen::Vector3d ra(a.position[0], a.position[1], a.position[2]);
  const Eigen::Vector3d Q(a.points[1].at[0], a.points[1].at[1], a.points[1].at[2]);
  const Eigen::Vector3d P(b.points[0].at[0], b.points[0].at[1], b.points[0].at[2]);
  const Eigen::Vector3d rb = ra + Ra * Q + shift - Rb * P;
  b.position = {rb[0], rb[1], dim == 2 ? 0.0 : rb[2]};
  return m;
}

/// The residuals of joint `joint`'s rows at (t, q).
std::vector<double> joint_residuals(const MultibodyParts& p, int joint, double t,
                                    const Eigen::VectorXd& q) {
  auto s = p.system->clone();
  Eigen::VectorXd phi(s->constraints());
  s->position_residual(t, q, phi);
  std::vector<double> out;
  for (std::size_t i = 0; i < p.row_joint.size(); ++i)
    if (p.row_joint[i] == joint) out.push_back(phi[static_cast<Eigen::Index>(i)]);
  return out;
}

}  // namespace

TEST_CASE("multibody: every joint's rows vanish where the joint holds, and only there") {
  for (int dim : {2, 3}) {
    std::vector<JointType> types = {JointType::revolute, JointType::prismatic, JointType::fixed,
                                    JointType::distance, JointType::point_on_line};
    if (dim == 3) {
      types.insert(types.end(), {JointType::spherical, JointType::universal, JointType::cylindrical,
                                 JointType::point_on_plane});
    }
    for (const JointType type : types) {
      CAPTURE(dim);
      CAPTURE(std::string(to_string(type)));
      const MultibodyParts p = build_multibody(assembled(dim, type));
      for (const double r : joint_residuals(p, 1, 0.0, p.q0)) CHECK(std::abs(r) < kRoundoff * 4);
      // Body b moved off: some row of the joint sees it (b turned about a direction no joint
      // frees, and shifted along all three axes).
      Eigen::VectorXd q = p.q0;
      const int o = dim == 2 ? 4 : 12;
      q.segment(o, dim) += Eigen::Vector3d(0.011, -0.013, 0.017).head(dim);
      double worst = 0.0;
      for (const double r : joint_residuals(p, 1, 0.0, q)) worst = std::max(worst, std::abs(r));
      CHECK(worst > 1e-3);
    }
  }
}

TEST_CASE("multibody: a drive prescribes the relative angle or slide counted from t = 0") {
  const double t = 0.9, theta = 0.5, slide = 0.2;
  for (int dim : {2, 3}) {
    for (const JointType type : {JointType::revolute, JointType::prismatic}) {
      CAPTURE(dim);
      CAPTURE(std::string(to_string(type)));
      Mechanism m = assembled(dim, type);
      m.joints[1].drive =
          type == JointType::revolute ? harmonic(0.4, 1.7, 0.0) : polynomial_drive();
      const MultibodyParts p = build_multibody(m);
      const double d = m.joints[1].drive->value(t);
      // Turn b about the joint axis by theta (right-hand rule), or slide it along the axis.
      const auto& a = m.bodies[0];
      const Eigen::Matrix3d Ra = a.orientation.toRotationMatrix();
      const Eigen::Vector3d axis =
          dim == 2 ? Eigen::Vector3d::UnitZ()
                   : Eigen::Vector3d(
                         Ra * Eigen::Vector3d(a.axes[0].at[0], a.axes[0].at[1], a.axes[0].at[2]));
      Eigen::VectorXd q = p.q0;
      const int o = dim == 2 ? 4 : 12;
      double expected = 0.0;
      if (type == JointType::revolute) {
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(theta, axis).matrix();
        if (dim == 2) {
          q.segment(o + 2, 2) = (turn * Eigen::Vector3d(q[o + 2], q[o + 3], 0.0)).head(2);
        } else {
          for (int k = 0; k < 3; ++k)
            q.segment(o + 3 + 3 * k, 3) = turn * Eigen::Vector3d(q.segment(o + 3 + 3 * k, 3));
        }
        expected = std::sin(theta - d);
      } else {
        const Eigen::Vector3d along =
            Ra * Eigen::Vector3d(a.axes[0].at[0], a.axes[0].at[1], a.axes[0].at[2]);
        q.segment(o, dim) += slide * along.head(dim);
        expected = slide - d;
      }
      const std::vector<double> rows = joint_residuals(p, 1, t, q);
      CHECK(std::abs(rows.back() - expected) < kRoundoff);
      CHECK(p.rows[p.rows.size() - 1].name == "tested.drive");
    }
  }
}

TEST_CASE("multibody energy parts: the forces' power is the loads' minus dV/dt minus dissipation") {
  for (int dim : {2, 3}) {
    const MultibodyParts p = build_multibody(two_bodies(dim, JointType::revolute, false));
    auto s = p.system->clone();
    const State st = generic_state(p);
    const double t = 0.6;
    Eigen::VectorXd f(st.u.size());
    s->force(t, st.u, st.v, f);
    const auto parts = s->energy_parts(t, st.u, st.v);
    REQUIRE(parts);
    CHECK_FALSE(s->energy(t, st.u, st.v));  // dampers, torques, time-dependent forces
    const double h = 1e-6;
    const double dV = (s->energy_parts(t, st.u + h * st.v, st.v)->potential -
                       s->energy_parts(t, st.u - h * st.v, st.v)->potential) /
                      (2 * h);
    CAPTURE(dim);
    // f·v = f_ext·v − ∇V·v − vᵀC v with C the dampers': a central difference of O(10) potentials
    // (truncation h² |V'''|, roundoff eps |V| / h, both below 1e-8 of the powers' size, about 10).
    CHECK(std::abs(f.dot(st.v) - (parts->load_power - dV - parts->dissipation_power)) <
          1e-7 * 10.0);
    CHECK(parts->dissipation_power > 0.0);
    CHECK(parts->load_power != 0.0);
  }
}

TEST_CASE("multibody outputs: angular acceleration from R'' = α × R + ω × (ω × R)") {
  for (int dim : {2, 3}) {
    const Mechanism m = two_bodies(dim, JointType::revolute, false);
    const MultibodyParts p = build_multibody(m);
    const Eigen::Vector3d alpha(dim == 3 ? 0.3 : 0.0, dim == 3 ? -0.8 : 0.0, 1.1);
    Eigen::VectorXd a = Eigen::VectorXd::Zero(p.q0.size());
    for (int b = 0; b < 2; ++b) {
      const auto& w = m.bodies[static_cast<std::size_t>(b)].angular_velocity;
      const Eigen::Vector3d omega(w[0], w[1], w[2]);
      const int o = b * (dim == 2 ? 4 : 12);
      a.segment(o, dim) = Eigen::Vector3d(0.4, -0.2, 0.1).head(dim);
      for (int k = 0; k < (dim == 2 ? 1 : 3); ++k) {
        const int at = dim == 2 ? o + 2 : o + 3 + 3 * k;
        Eigen::Vector3d Rk = Eigen::Vector3d::Zero();
        Rk.head(dim) = p.q0.segment(at, dim);
        const Eigen::Vector3d second = alpha.cross(Rk) + omega.cross(omega.cross(Rk));
        a.segment(at, dim) = second.head(dim);
      }
    }
    Eigen::VectorXd out;
    p.outputs->acceleration(0.0, p.q0, p.v0, a, out);
    CAPTURE(dim);
    const int cols = dim == 2 ? 3 : 6;
    for (int b = 0; b < 2; ++b) {
      for (int r = 0; r < dim; ++r) CHECK(out[b * cols + r] == a[b * (dim == 2 ? 4 : 12) + r]);
      for (int r = 0; r < (dim == 2 ? 1 : 3); ++r) {
        // Products of O(1) unit vectors and rates: roundoff.
        CHECK(std::abs(out[b * cols + dim + r] - alpha[dim == 2 ? 2 : r]) < kRoundoff);
      }
    }
  }
}

}  // namespace test_multibody_system
