// IDA's return flags as failure kinds (dae/integrators/ida_failure_kind.hpp).

#include "dae/integrators/ida_failure_kind.hpp"

#include <ida/ida.h>

namespace condyn {

FailureKind ida_failure_kind(int flag) {
  switch (flag) {
    case IDA_TOO_MUCH_WORK:
      return FailureKind::steps_per_output;
    case IDA_TOO_MUCH_ACC:
      return FailureKind::tolerance_too_tight;
    case IDA_ERR_FAIL:
      return FailureKind::error_test;
    case IDA_CONV_FAIL:
    case IDA_NLS_FAIL:
    case IDA_NLS_SETUP_FAIL:
    case IDA_NO_RECOVERY:
    case IDA_LINESEARCH_FAIL:
      return FailureKind::convergence;
    case IDA_LINIT_FAIL:
    case IDA_LSETUP_FAIL:
    case IDA_LSOLVE_FAIL:
      return FailureKind::linear_solver;
    case IDA_REP_RES_ERR:  // the residual stayed non-finite however small the step
      return FailureKind::residual_non_finite;
    case IDA_ILL_INPUT:
    case IDA_BAD_EWT:
    case IDA_BAD_T:
    case IDA_BAD_K:
    case IDA_BAD_DKY:
      return FailureKind::bad_input;
    default:
      return FailureKind::unknown;
  }
}

}  // namespace condyn
