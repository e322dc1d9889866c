#pragma once
/// An equation that cannot be evaluated at a trial state the integrator chose (a singular KKT
/// system at a guessed configuration, say): thrown by a problem's residual or right-hand side,
/// turned into the recoverable return value +1 by the SUNDIALS trampolines, so the integrator
/// cuts its step and tries again instead of ending the run. Only when it keeps failing does the
/// run fail, and its message then quotes the last of these.

#include <stdexcept>

namespace condyn {

class RecoverableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace condyn
