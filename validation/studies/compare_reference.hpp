#pragma once
/// What the runs of `condyn compare` are scored against (compare_reference.cpp): the best
/// reference available and the error scales, and the settings and progress hooks that its
/// reference runs share with the sweep's (compare.cpp).

#include <string>

#include "dae/run/solve.hpp"
#include "validation/studies/compare.hpp"

namespace condyn {

/// The scene's run settings with the scheme and tolerances of one run of the sweep.
[[nodiscard]] SolveSpec settings_of(const SolveSpec& scene, Scheme scheme, double rtol,
                                    double atol);

/// Hooks that report a long run's progress through options.progress, each line led by `what`
/// ("[3/8] projection rtol 1.0e-06"): a sweep whose run takes minutes says which one it is.
[[nodiscard]] RunHooks progress_hooks(const CompareOptions& options, const std::string& what);

/// The reference at the output rows (the published state alone for a benchmark), with its kind,
/// description, error scales and multiplier history in `out`. The reference is computed on a
/// grid kScaleSamples times finer than the output rows, for scales of the whole run. Throws
/// NoReferenceError when there is none.
[[nodiscard]] Trajectory reference_at_rows(const Model& base, const SolveSpec& scene,
                                           const CompareOptions& options, CompareResult& out);

}  // namespace condyn
