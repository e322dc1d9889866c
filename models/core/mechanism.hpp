#pragma once
/// A mechanism of rigid bodies as the scene describes it ([model] type = "multibody",
/// docs/scenes.md "Mechanisms of rigid bodies"): bodies with mass, inertia, pose and velocity at
/// t = 0 and named markers; joints between two bodies (or a body and the ground); force elements;
/// gravity. Plain data, checked by the scene reader (models/scene/read_mechanism*.cpp) and turned
/// into a MechanicalSystem by models/systems/multibody_system.hpp. Every vector has 3 entries; in
/// 2D the third is 0 and unused.

#include <Eigen/Dense>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/source_point.hpp"
#include "models/core/time_function.hpp"

namespace condyn {

struct Mechanism {
  using Vec3 = std::array<double, 3>;

  /// A named point (in `points`) or unit vector (in `axes`), in the body frame (the ground's:
  /// global).
  struct Marker {
    std::string name;
    Vec3 at{};
  };

  struct Body {
    std::string name;
    double mass = 0.0;
    /// About the centre of mass, body frame. 2D: only (2, 2) is used (the scalar inertia).
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    Vec3 position{};  ///< centre of mass at t = 0
    /// Orientation at t = 0: body frame to global. 2D: a rotation about z by the scene's `angle`
    /// (angle = atan2 of its (1, 0) and (0, 0) entries; `angle` itself kept for the output's
    /// unwrapped start).
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    double angle = 0.0;       ///< 2D: the scene's angle
    Vec3 velocity{};          ///< centre-of-mass velocity at t = 0
    Vec3 angular_velocity{};  ///< global; 2D: only [2] is used
    std::vector<Marker> points, axes;
    SourcePoint where;
  };

  enum class JointType {
    revolute,
    prismatic,
    fixed,
    distance,
    point_on_line,
    spherical,       ///< 3D only
    universal,       ///< 3D only
    cylindrical,     ///< 3D only
    point_on_plane,  ///< 3D only
  };

  /// Body index of the ground in Joint::bodies and Force::bodies.
  static constexpr int kGround = -1;

  struct Joint {
    std::string name;
    JointType type = JointType::revolute;
    std::array<int, 2> bodies{kGround, kGround};  ///< body indices, kGround for the ground
    /// Indices into each body's `points` (the ground's: ground_points).
    std::array<int, 2> points{0, 0};
    /// Indices into each body's `axes` (the ground's: ground_axes); -1 where the joint type
    /// needs none or the scene gave none.
    std::array<int, 2> axes{-1, -1};
    std::optional<double> length;       ///< distance joint; nothing: the distance at t = 0
    std::optional<TimeFunction> drive;  ///< revolute: relative angle; prismatic: slide; 0 at t = 0
    SourcePoint where;
  };

  enum class ForceType { spring_damper, rotational_spring_damper, point_force, torque };

  struct Force {
    ForceType type = ForceType::spring_damper;
    std::array<int, 2> bodies{kGround, kGround};  ///< spring_damper: both; point_force, torque: [0]
    std::array<int, 2> points{0, 0};              ///< spring_damper: both; point_force: [0]
    double k = 0.0, c = 0.0;
    std::optional<double> rest_length;  ///< spring_damper; nothing: the length at t = 0
    double rest_angle = 0.0;            ///< rotational_spring_damper: relative to the t = 0 angle
    int joint = -1;                     ///< rotational_spring_damper: a revolute joint's index
    /// point_force: one per dimension (global); torque: 1 in 2D, 3 in 3D (global).
    std::vector<TimeFunction> components;
    SourcePoint where;
  };

  int dimension = 2;
  Vec3 gravity{};
  std::vector<Marker> ground_points, ground_axes;
  std::vector<Body> bodies;
  std::vector<Joint> joints;
  std::vector<Force> forces;
  SourcePoint where;  ///< the [model] table
};

[[nodiscard]] const char* to_string(Mechanism::JointType type);

/// What a body's rigid-body rows are named after the body's name: "<body>.rigid" in 2D (its unit
/// x axis), "<body>.rigid_xx" … "<body>.rigid_yz" in 3D (its rotation's unit and orthogonal
/// columns). Joints' rows are named "<joint>.<what>" with other endings.
inline constexpr std::string_view kRigidRow = "rigid";

/// The body whose rigid-body row `row_name` is ("rod1" of "rod1.rigid" or "rod1.rigid_xy"), or ""
/// for any other row (a joint's).
[[nodiscard]] std::string rigid_row_body(std::string_view row_name);

}  // namespace condyn
