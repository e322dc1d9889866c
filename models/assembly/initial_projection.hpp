#pragma once
/// [initial] project = true: moves (u0, v0) onto the constraint manifold, keeping the values the
/// scene gave ([initial] displacement / velocity) and changing only the others, by the smallest
/// mass-weighted change among them. With F the DOFs not given and W = diag(M(t, u0)) on F
/// (massless DOFs weigh as the lightest DOF with mass, so they are no obstacle):
///   position rows:  Gauss-Newton  min ‖W^½ Δu_F‖  s.t.  A_p,F Δu_F = −φ_p(t, u)  (least squares
///                   when the given values leave no exact solution), until the step is at roundoff;
///   all rows:       min ‖W^½ Δv_F‖  s.t.  A_F Δv_F = −ψ(t, u, v)  (ψ is affine in u': exact,
///                   repeated once to clean up roundoff).
/// When a constraint cannot be met with the given values fixed, the given values are themselves
/// inconsistent: InconsistentGivenValues names the constraint, its residual and the given DOFs it
/// involves (the caller refuses the scene; nothing the user wrote is overridden silently).
/// Dense factorizations: meant for the initial state of small and medium models.

#include <Eigen/Dense>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/core/mechanical_system.hpp"

namespace condyn {

/// A constraint row counts as met at the initial state when its residual is below this relative
/// size: a scene writes initial values by hand in decimal, so a few hundred ulps of the terms'
/// size is the right scale. Shared by build_model's consistency check and the projection.
inline constexpr double kConsistencyTolerance = 1e-10;

/// Thrown by project_initial_state when the given values leave constraints violated.
class InconsistentGivenValues : public std::runtime_error {
 public:
  InconsistentGivenValues(const std::string& what, bool at_velocity_level,
                          std::vector<std::pair<int, double>> violated_rows,
                          std::vector<int> given_dofs)
      : std::runtime_error(what),
        velocity_level(at_velocity_level),
        violated(std::move(violated_rows)),
        given(std::move(given_dofs)) {}
  bool velocity_level;  ///< violated at velocity level (else position level)
  /// (row, residual) of each constraint left violated at the closest reachable state, scene order;
  /// found with the rows that involve no given value held (nearly) exactly, so the residual
  /// lands on the rows that do.
  std::vector<std::pair<int, double>> violated;
  std::vector<int> given;  ///< the given DOFs those rows act on there (nonzero in A), ascending
};

/// Projects in place. `given_u[i]` / `given_v[i]` mark the DOFs whose value the scene wrote (kept
/// fixed). Returns the report `run` and `info` print: one summary line, then one line per DOF that
/// moved ("  ux3: displacement 0 -> 0.25"), at most 20 lines, the rest counted.
/// Throws InconsistentGivenValues (above), or std::runtime_error when the constraints cannot be
/// met at all near u0 (the iteration does not converge) or a violated row does not change to
/// first order along the free DOFs at u0 (naming it: `constraint_names`, one per row).
std::string project_initial_state(MechanicalSystem& system, double t, Eigen::VectorXd& u,
                                  Eigen::VectorXd& v, const std::vector<bool>& given_u,
                                  const std::vector<bool>& given_v,
                                  const std::vector<std::string>& dof_names,
                                  const std::vector<std::string>& constraint_names);

}  // namespace condyn
