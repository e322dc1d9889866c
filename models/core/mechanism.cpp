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

std::string rigid_row_body(std::string_view row_name) {
  const std::size_t dot = row_name.rfind('.');
  if (dot == std::string_view::npos || dot == 0) return "";
  const std::string_view what = row_name.substr(dot + 1);
  // "rigid" in 2D; "rigid_" and two axis letters in 3D.
  const bool rigid =
      what == kRigidRow || (what.size() == kRigidRow.size() + 3 && what.starts_with(kRigidRow) &&
                            what[kRigidRow.size()] == '_');
  return rigid ? std::string(row_name.substr(0, dot)) : "";
}

}  // namespace condyn
