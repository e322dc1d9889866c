#pragma once
/// [initial] keep of a body's angular velocity (models/core/mechanism_keep.hpp) while the start
/// is projected: a mechanism's system with one more velocity-level row per kept component,
///   2D:  ω  = u_x u_y' − u_y u_x' − ω₀ = 0          (u the body's unit x axis),
///   3D:  ω_i = ½ Σ_k (R_k × R_k')_i − ω₀_i = 0     (R_k the columns of its rotation),
/// exact on the rigid rows' manifold, linear in the velocities: the projection's velocity step
/// (models/assembly/initial_projection.hpp) then meets it with the joints, so the kept value is
/// exact where the positions land. Only what the projection evaluates is defined: mass, A, φ, ψ.

#include <memory>
#include <vector>

#include "models/core/mechanical_system.hpp"

namespace condyn {

struct KeptRotationRow {
  std::vector<int> axes;  ///< 2D: the indices of u_x, u_y; 3D: R11, R21, R31, R12, …, R33
  int component = 2;      ///< 0..2: the global component kept (2D: 2)
  double value = 0.0;     ///< ω₀
};

/// `base` with the rows `kept` after its own.
[[nodiscard]] std::unique_ptr<MechanicalSystem> with_kept_rotations(
    std::unique_ptr<MechanicalSystem> base, std::vector<KeptRotationRow> kept);

}  // namespace condyn
