#pragma once
/// What to try after a failed run, in one line: chosen by the failure's kind, worded from the facts
/// it carries (time reached against t0 and t_end, last step, steps, wall time), with what the
/// scheme itself adds (its gains, its weight, its drift).

#include <string>

#include "dae/solve_result.hpp"
#include "models/scheme.hpp"

namespace condyn {

[[nodiscard]] std::string failure_suggestion(Scheme scheme, const RunFailure& e);

}  // namespace condyn
