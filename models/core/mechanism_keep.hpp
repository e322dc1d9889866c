#pragma once
/// The values `[initial] keep` names in a mechanism (docs/scenes.md, "Mechanisms of rigid
/// bodies"): "body.key", where key is an output column of the body's pose or velocity (x, y, z,
/// angle; vx, vy, vz, omega, wx, wy, wz) or a [[body]] key (position, angle, orientation,
/// velocity, angular_velocity). The scene reader checks the names with it; the builder keeps the
/// values it describes while projecting the start (models/assembly/multibody_model.cpp).

#include <string>
#include <vector>

#include "models/core/mechanism.hpp"

namespace condyn {

struct KeptValue {
  enum class Kind {
    position,          ///< a component of the centre of mass
    orientation,       ///< the whole orientation (2D: the angle)
    velocity,          ///< a component of the centre of mass' velocity
    angular_velocity,  ///< a global component of the angular velocity (2D: 2, about z)
  };
  int body = 0;  ///< index into Mechanism::bodies
  Kind kind = Kind::position;
  int component = 0;  ///< 0..2 (x, y, z); unused for orientation
};

/// What `name` keeps, one entry per component (crank.position in 2D: x and y). Empty, with
/// `problem` saying why, when the name is not one of them.
[[nodiscard]] std::vector<KeptValue> kept_values(const Mechanism& mechanism,
                                                 const std::string& name, std::string& problem);

}  // namespace condyn
