#pragma once
/// What an IDA return flag says happened, by its code, never its text: the kind a failed run
/// reports (FailureKind, dae/integrators/step_driver.hpp).

#include "dae/integrators/step_driver.hpp"

namespace condyn {

/// The kind of IDA's negative return flag `flag`; FailureKind::unknown for a flag not listed.
[[nodiscard]] FailureKind ida_failure_kind(int flag);

}  // namespace condyn
