#pragma once
/// A mechanism of rigid bodies (models/core/mechanism.hpp) as a MechanicalSystem in natural
/// coordinates (docs/schemes.md, "Coordinates of rigid bodies"):
///
///   2D  body b: q_b = (r_x, r_y, u_x, u_y): the centre of mass r and the body's x axis u, a unit
///       vector (its y axis is u rotated by +90°, linear in u); 1 rigid row (|u|² − 1)/2 = 0;
///       M_b = diag(m, m, I, I) (kinetic energy ½ m |r'|² + ½ I |u'|²).
///   3D  body b: q_b = (r, R_1, R_2, R_3): the centre of mass and the columns of the rotation
///       matrix R (body frame to global); 6 rigid rows (|R_k|² − 1)/2 = 0, R_j·R_k = 0;
///       M_b = blockdiag(m I₃, J ⊗ I₃) with J = ∫ s sᵀ dm = ½ tr(I) 1 − I (constant).
///
/// A marker s of a body is at r + R s, and a body-fixed vector e points along R e: both linear in
/// q. Every joint row and every rigid row is then a quadratic form in q whose coefficients may
/// depend on t through a drive (rheonomic rows), so A, γ and all their derivatives are exact and
/// sparse. The mass matrix is constant; gravity and point forces are constant maps of t.

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "models/core/mechanical_system.hpp"
#include "models/core/mechanism.hpp"
#include "models/core/model.hpp"
#include "models/core/output_map.hpp"

namespace condyn {

/// What the builder needs to make a Model of a mechanism.
struct MultibodyParts {
  std::shared_ptr<const MechanicalSystem> system;
  std::shared_ptr<const OutputMap> outputs;
  /// The natural coordinates' names, n of them: "crank.rx", "crank.ry", "crank.ux", "crank.uy"
  /// in 2D; "crank.rx" … "crank.rz", "crank.R11" … "crank.R33" (R_ij: row i of column j) in 3D.
  std::vector<std::string> coordinate_names;
  /// One per row, in the system's row order: the bodies' rigid rows first (name "crank.rigid",
  /// "crank.rigid_xy", …), then each joint's rows in scene order ("hinge_O.x", "hinge_O.y",
  /// "hinge_O.drive", …). `coefficients` empty (nonlinear rows) except where a row is linear with
  /// constant coefficients; `nonlinear_kind` says what the row holds ("point A of crank on point O
  /// of ground, x"); `where` is the joint's (the body's for rigid rows).
  std::vector<Constraint> rows;
  /// The joint each row belongs to (index into Mechanism::joints), −1 for rigid rows.
  std::vector<int> row_joint;
  /// Whether each row depends on t (a drive's rows: rheonomic).
  std::vector<bool> row_rheonomic;
  /// q and q' at t = 0 from the bodies' poses and velocities (exactly on the rigid rows).
  Eigen::VectorXd q0, v0;
};

/// Builds the system, its output map and its rows. The mechanism is assumed checked by the scene
/// reader (known bodies, points and axes; positive definite inertia; unit quaternions).
[[nodiscard]] MultibodyParts build_multibody(const Mechanism& mechanism);

}  // namespace condyn
