#pragma once
/// The constraint rows of a mechanism in natural coordinates, each a sum of quadratic forms
/// (models/systems/quadratic_rows.hpp): the bodies' rigid rows, then each joint's rows in scene
/// order, scaled so that a row's drift reads as a length or an angle (radians, for small values).
///
/// Notation per joint: p1, p2 its points on bodies 1 and 2, d = p2 − p1; a1 body 1's axis (when
/// the scene gives none: body 1's x axis in 2D, its z axis in 3D), b1, c1 a
/// body-1-fixed orthonormal completion (c1 = a1 × b1; 2D: b1 = u1, c1 = perp(u1)); a2 body 2's
/// axis (default: the body-2-fixed vector equal to a1 at t = 0); e2 the body-2-fixed vector
/// equal to b1 at t = 0.
///
///   2D revolute      d = 0 (x, y)                  prismatic   a1 × a2 = 0, a1 × d = 0
///      fixed         d = 0, u1 × e2 = 0            distance    (|d|² − L²)/(2L) = 0
///      point_on_line a1 × d = 0
///   3D spherical     d = 0 (x, y, z)               revolute    spherical, a2·b1 = a2·c1 = 0
///      cylindrical   a2·b1 = a2·c1 = 0, d·b1 = d·c1 = 0
///      prismatic     cylindrical, e2·c1 = 0        universal   spherical, a1·a2 = 0
///      point_on_line d·b1 = d·c1 = 0               point_on_plane d·a1 = 0 (a1 the normal)
///      fixed         spherical, e2x·F1y = e2x·F1z = e2y·F1z = 0 (F1 body 1's frame, e2k the
///                    body-2-fixed vectors equal to F1k at t = 0)
///      distance      as in 2D
///   drives           revolute: (e2·c1) cos θ(t) − (e2·b1) sin θ(t) = sin(relative angle − θ(t))
///                    prismatic: d·a1 − s0 − s(t) = 0 (s0 the slide d·a1 at t = 0)
///
/// Throws std::invalid_argument for what the scene reader refuses (a 3D joint in 2D, a drive on
/// a joint without a coordinate, a distance joint of length 0).

#include <string>
#include <vector>

#include "models/core/mechanism.hpp"
#include "models/core/source_point.hpp"
#include "models/core/time_function.hpp"
#include "models/systems/multibody_geometry.hpp"
#include "models/systems/quadratic_rows.hpp"

namespace condyn {

struct MultibodyRow {
  std::string name;  ///< "crank.rigid", "hinge_O.x", "hinge_O.drive"
  std::string kind;  ///< what the row says
  std::vector<QuadraticTerm> terms;
  int joint = -1;  ///< index into Mechanism::joints; −1 for rigid rows
  SourcePoint where;
};

struct MultibodyRowSet {
  std::vector<MultibodyRow> rows;
  std::vector<TimeFunction> drives;  ///< the drives the rows' terms name
};

/// Every row of the mechanism: the rigid rows of each body, then the joints'.
[[nodiscard]] MultibodyRowSet multibody_rows(const Mechanism& m, const MultibodyGeometry& g);

/// The relative rotation of a revolute joint about its axis as two quadratic forms: x = e2·b1 =
/// cos θ and y = e2·c1 = sin θ (θ = 0 at t = 0); the rotational spring-damper's angle.
struct RelativeAngle {
  QuadraticForm x, y;
};
/// q0: the coordinates at t = 0 (MultibodyGeometry::initial_coordinates).
[[nodiscard]] RelativeAngle relative_angle(const Mechanism& m, const MultibodyGeometry& g,
                                           const Eigen::VectorXd& q0, int joint);

}  // namespace condyn
