#pragma once
/// `condyn validate`: the chapter's five cases, matrices against the printed ones, the elimination
/// path against the exact modal solution, and the errata the code finds; then the published
/// benchmarks (validation/references/benchmark_suite.hpp).

#include <ostream>

#include "models/core/scheme.hpp"

namespace condyn {

struct ValidationOptions {
  bool quiet = false;  ///< tables only, no matrices
};

/// Integrated results must agree with the exact solution to this multiple of rtol (relative
/// max-norm over output times). IDA controls the local error of each step; the global error is
/// that accumulated over ~10³ steps of undamped oscillation, and the relative measure is further
/// inflated where a rigid-body mode makes the displacements large next to the elastic part that
/// drives the reactions (case D). Observed at rtol = 1e-10 over every scheme: error/rtol from 1
/// (case B, u, elimination) to 270 (case A, u', GGL); `condyn validate` prints the figures every
/// run. 1000 keeps a margin of 3.7 for other compilers and machines and is still 10x inside the
/// issue's acceptance level (1e-6 at rtol = 1e-10); an O(1) error in any term misses it by orders
/// of magnitude.
inline constexpr double kGlobalErrorFactor = 1000.0;

/// The schemes every case runs under, the chapter's reference path first.
/// index2, index3 and penalty are left to `compare`: their accuracy per tolerance is their own
/// (index3's multipliers, penalty's 1/w error), not this suite's common factor.
inline constexpr Scheme kValidatedSchemes[] = {Scheme::elimination, Scheme::index1,
                                               Scheme::baumgarte, Scheme::ggl, Scheme::projection};

/// Runs the suite, prints the report; true when every comparison is within its tolerance.
bool run_validation(std::ostream& out, const ValidationOptions& options);

}  // namespace condyn
