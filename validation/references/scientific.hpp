#pragma once
/// A figure in a report or message: v in scientific notation with `digits` after the point
/// (scientific(3.28e-9, 1) is "3.3e-09").

#include <iomanip>
#include <sstream>
#include <string>

namespace condyn {

[[nodiscard]] inline std::string scientific(double v, int digits) {
  std::ostringstream s;
  s << std::scientific << std::setprecision(digits) << v;
  return s.str();
}

}  // namespace condyn
