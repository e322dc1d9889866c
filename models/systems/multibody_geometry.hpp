#pragma once
/// Where things are in a mechanism's natural coordinates (models/systems/multibody_system.hpp):
/// body b's coordinates start at b · body_size (4 in 2D: r, u; 12 in 3D: r, R_1, R_2, R_3); a
/// marker s of body b is at r + R s, a body-fixed vector e points along R e, both affine in q;
/// the ground's markers are constants. Shared by the system, its rows and its output map.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "models/core/mechanism.hpp"
#include "models/systems/quadratic_rows.hpp"

namespace condyn {

class MultibodyGeometry {
 public:
  using Vector = Eigen::VectorXd;
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;

  explicit MultibodyGeometry(const Mechanism& mechanism);

  [[nodiscard]] int dimension() const { return dim_; }
  /// Coordinates per body: 4 (2D) or 12 (3D).
  [[nodiscard]] int body_size() const { return dim_ == 2 ? 4 : 12; }
  [[nodiscard]] int coordinates() const { return body_size() * bodies_; }
  [[nodiscard]] int offset(int body) const { return body * body_size(); }

  /// The global position r + R s of the body-frame point s of `body` (the ground's: s itself).
  [[nodiscard]] AffineVector point(int body, const Eigen::Vector3d& s) const;
  /// The global direction R e of the body-frame vector e (the ground's: e itself).
  [[nodiscard]] AffineVector direction(int body, const Eigen::Vector3d& e) const;
  /// The body's marker `index` of `points` (the ground's: ground_points), body frame.
  [[nodiscard]] Eigen::Vector3d marker(const Mechanism& m, int body, int index) const;
  /// The body's unit vector `index` of `axes` (the ground's: ground_axes), body frame, normalized.
  [[nodiscard]] Eigen::Vector3d axis(const Mechanism& m, int body, int index) const;

  /// R of `body` at q (3 x 3; in 2D [u, perp(u)] in the xy block and 1 on z); the identity for
  /// the ground.
  [[nodiscard]] Eigen::Matrix3d rotation(int body, const ConstRef& q) const;
  /// The centre of mass (3 entries; z = 0 in 2D).
  [[nodiscard]] Eigen::Vector3d position(int body, const ConstRef& q) const;
  /// q and q' at t = 0 from the bodies' poses and velocities.
  [[nodiscard]] Vector initial_coordinates(const Mechanism& m) const;
  [[nodiscard]] Vector initial_velocities(const Mechanism& m) const;

 private:
  int dim_ = 2, bodies_ = 0;
};

/// The scene's orientation of a body at t = 0 as a rotation matrix: in 2D a rotation about z by
/// its `angle`, in 3D its normalized quaternion's.
[[nodiscard]] Eigen::Matrix3d initial_rotation(const Mechanism& m, int body);

}  // namespace condyn
