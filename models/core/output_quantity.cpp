#include "models/core/output_quantity.hpp"

namespace condyn {

const char* to_string(Quantity q) {
  switch (q) {
    case Quantity::displacement:
      return "displacement";
    case Quantity::velocity:
      return "velocity";
    case Quantity::acceleration:
      return "acceleration";
    case Quantity::absolute_acceleration:
      return "absolute_acceleration";
    case Quantity::reaction:
      return "reaction";
    case Quantity::multiplier:
      return "multiplier";
    case Quantity::drift:
      return "drift";
    case Quantity::energy:
      return "energy";
  }
  return "?";
}

}  // namespace condyn
