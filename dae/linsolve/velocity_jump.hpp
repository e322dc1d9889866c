#pragma once
/// The velocity jump at a restart where a drive's rate changes (a table's sample): v ← v + Δv with
/// [M Aᵀ; A 0] [Δv; Λ] = [0; −ψ(t, u, v)], the least change of kinetic energy that meets the
/// velocity rows at t (the drive's impulse Aᵀ Λ). Shared by the multiplier schemes' restart
/// (MultiplierDae::jump_velocities) and the Newmark family's (NewmarkStepper::restart).

#include <Eigen/Dense>

#include "models/core/mechanical_system.hpp"

namespace condyn {

/// Moves v (n) onto the velocity rows at (t, u) as above; leaves it when the system has no
/// curvature (a linear model: its rows keep their rate) or no constraints, or when [M Aᵀ; A 0]
/// is singular (the caller's consistency solve reports that).
void jump_onto_velocity_rows(MechanicalSystem& system, double t, const Eigen::VectorXd& u,
                             Eigen::VectorXd& v);

}  // namespace condyn
