#pragma once
/// `condyn validate`: the chapter's five cases, matrices against the printed ones, the elimination
/// path against the exact modal solution, and the errata the code finds.

#include <ostream>

namespace condyn {

struct ValidationOptions {
  bool quiet = false;  ///< tables only, no matrices
};

/// Integrated results must agree with the exact solution to this multiple of rtol (relative
/// max-norm over output times). IDA controls the local error per step; the global error after
/// hundreds of steps of an undamped oscillator is larger by the error growth over the horizon.
/// Observed on the five cases at rtol = 1e-10: ratios up to ~30 (velocities of case D); 100 leaves
/// a margin for compilers and machines without hiding an O(1) mistake.
inline constexpr double kGlobalErrorFactor = 100.0;

/// Runs the suite, prints the report; true when every comparison is within its tolerance.
bool run_validation(std::ostream& out, const ValidationOptions& options);

}  // namespace condyn
