#pragma once
/// The refusal of a scheme that cannot treat a model: thrown by dispatch and by the formulations
/// that find out while they are set up (the reduced ODE of elimination).

#include <stdexcept>
#include <string>
#include <utility>

#include "models/core/source_point.hpp"

namespace condyn {

/// Thrown when a scheme cannot treat a model (the reason is scheme_refusal's): the request, not the
/// solver, is at fault, so the CLI answers it as bad input (exit 2).
class SchemeNotApplicable : public std::invalid_argument {
 public:
  explicit SchemeNotApplicable(const std::string& why, SourcePoint where = {})
      : std::invalid_argument(why), where_(std::move(where)) {}
  /// Where the refused scheme was chosen (SolveSpec::scheme_where) once plan() or system_size()
  /// has passed it on; empty before, and for a scheme nobody named (auto).
  [[nodiscard]] const SourcePoint& where() const { return where_; }

 private:
  SourcePoint where_;
};

}  // namespace condyn
