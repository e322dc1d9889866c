#include "models/core/mechanism.hpp"

namespace condyn {

const char* to_string(Mechanism::JointType type) {
  switch (type) {
    case Mechanism::JointType::revolute:
      return "revolute";
    case Mechanism::JointType::prismatic:
      return "prismatic";
    case Mechanism::JointType::fixed:
      return "fixed";
    case Mechanism::JointType::distance:
      return "distance";
    case Mechanism::JointType::point_on_line:
      return "point_on_line";
    case Mechanism::JointType::spherical:
      return "spherical";
    case Mechanism::JointType::universal:
      return "universal";
    case Mechanism::JointType::cylindrical:
      return "cylindrical";
    case Mechanism::JointType::point_on_plane:
      return "point_on_plane";
  }
  return "unknown";
}

}  // namespace condyn
