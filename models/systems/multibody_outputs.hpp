#pragma once
/// A mechanism's output columns (scene-format "Mechanisms of rigid bodies", OutputMap) from its
/// natural coordinates q = (r, u) per body in 2D, (r, R_1, R_2, R_3) in 3D:
///
///   displacement  <body>.x .y (.z); 2D <body>.angle = atan2(u_y, u_x) continued from the
///                 previous row (from the scene's angle at the first row: no jump of 2π);
///                 3D <body>.qw .qx .qy .qz: the unit quaternion of R (Shepperd's method), its
///                 sign that of the previous row's (qw > 0 at the first row)
///   velocity      <body>.vx .vy (.vz); 2D <body>.omega = u × u'; 3D <body>.wx .wy .wz =
///                 ½ Σ_k R_k × R_k' (the axial vector of R' Rᵀ, global)
///   acceleration  <body>.ax .ay (.az); 2D <body>.alpha = u × u''; 3D ½ Σ_k R_k × R_k''
///   reaction      <joint>.fx .fy (.fz), <joint>.m (2D) or .mx .my .mz: the force and torque the
///                 joint's rows (drive included) apply to its second body, Q = −A_jointᵀλ on that
///                 body's coordinates: F = Q_r, torque about the centre of mass u × Q_u (2D) or
///                 Σ_k R_k × Q_{R_k} (3D), moved to the joint's point on that body. A joint
///                 whose second body is the ground reports minus what it applies to its first
///                 body, about the ground's point.
///   points        "body.point" (the ground's: "ground.point") at r + R s.

#include <memory>
#include <string>
#include <vector>

#include "models/core/mechanism.hpp"
#include "models/core/output_map.hpp"
#include "models/systems/multibody_geometry.hpp"
#include "models/systems/quadratic_rows.hpp"

namespace condyn {

class MultibodyOutputs final : public OutputMap {
 public:
  /// row_joint: the joint of each of the rows' rows (−1 for rigid rows).
  MultibodyOutputs(const Mechanism& m, std::shared_ptr<const QuadraticRows> rows,
                   const std::vector<int>& row_joint);

  [[nodiscard]] const std::vector<std::string>& names(Quantity q) const override;
  void displacement(double t, const Vector& u, const Vector& previous, Vector& out) const override;
  void velocity(double t, const Vector& u, const Vector& v, Vector& out) const override;
  void acceleration(double t, const Vector& u, const Vector& v, const Vector& a,
                    Vector& out) const override;
  void reaction(double t, const Vector& u, const Vector& lambda, Vector& out) const override;
  [[nodiscard]] std::optional<int> point(std::string_view name) const override;
  void point_position(int index, const Vector& u, Eigen::Ref<Vector> out) const override;
  [[nodiscard]] int dimension() const override { return geometry_.dimension(); }

 private:
  struct Point {
    std::string name;
    int body;
    Eigen::Vector3d at;  ///< body frame (the ground's: global)
  };
  struct JointRef {
    int body1, body2;
    Eigen::Vector3d point1, point2;  ///< body frames
    std::vector<int> rows;
  };
  /// Per body: the columns of a rate (velocity or acceleration) w of the coordinates.
  void rates(const Vector& u, const Vector& w, Vector& out) const;
  /// (force, torque about the centre of mass) of generalized force Q on `body`'s coordinates.
  [[nodiscard]] std::pair<Eigen::Vector3d, Eigen::Vector3d> wrench(int body, const Vector& u,
                                                                   const Vector& Q) const;

  MultibodyGeometry geometry_;
  std::shared_ptr<const QuadraticRows> rows_;
  std::vector<double> start_angles_;  ///< 2D: each body's scene angle
  std::vector<Point> points_;
  std::vector<JointRef> joints_;
  std::vector<std::string> displacement_, velocity_, acceleration_, reaction_, none_;
};

}  // namespace condyn
