#pragma once
/// What integrating a model will hold in memory, estimated per scheme from the sizes of the system
/// it integrates before any solver work, and the refusal of a model that will not fit in the
/// machine's available memory.

#include <optional>
#include <string>

namespace condyn {

/// The model's sizes: DOFs n, constraints m, and the nonzeros of M, C, K and A.
struct ModelSizes {
  double dofs = 0, constraints = 0;
  double nnz_mass = 0, nnz_damping = 0, nnz_stiffness = 0, nnz_constraints = 0;
};
struct Model;
[[nodiscard]] ModelSizes model_sizes(const Model& model);

/// What a scheme integrates (dae/run/scheme_memory.hpp fills it from SystemSize): the integrator's
/// unknowns, the nonzeros of the matrix its Newton iterations factor, and the entries of that
/// matrix's KLU factors L and U as predicted before factoring; `dense` for a dense Newton matrix
/// (IDA's dense linear solver when asked for): unknowns² doubles and no KLU;
/// `condensed` for a condensed Newton matrix (the projection's saddle point, [solve] newton =
/// "condensed"), whose solver keeps its own M, C, K, A and assembles the matrix afresh beside the
/// one it factors; `reduced` for a reduced model's system (elimination, the mixed treatment), whose
/// matrices are held beside the model's.
struct IntegratedSizes {
  double unknowns = 0;
  double newton_nonzeros = 0;
  double factor_entries = 0;
  /// The flops of factoring it as the same analysis predicts them; 0 when not known.
  double factor_flops = 0;
  /// When CHOLMOD factors the Newton matrix: its factor's bytes (values and indices) as its
  /// symbolic analysis predicts them, counted in place of KLU's L and U, and factor_entries the
  /// entries of L; 0 under KLU.
  double cholmod_factor_bytes = 0;
  bool dense = false;
  bool condensed = false;
  bool reduced = false;
};

/// Bytes a run holds at its peak, as the sum of:
///   the process before any model (the executable and its libraries, resident): kProcessBytes;
///   the model's matrices M, C, K, A: 12 B per nonzero (value and 32-bit row index) each, held
///     kModelCopies times (the Model, its system's evaluator, the formulation's blocks), once
///     more for a condensed Newton solver and once more for a reduced model (at most the model's
///     nonzeros);
///   the Newton matrix: 12 B per nonzero in the integrator's matrix and 4 B in its pattern, 12 B
///     more when condensed;
///   its KLU factors: 12 B per entry, twice when keeps_streamed_copy holds for the analysis's
///     counts (the copy the solves stream, dae/linsolve/klu_streamed_solve.hpp; the run decides
///     from its own factor's, under its own ordering: the two can differ near the threshold, but
///     a strip's 8 to 12 flops an entry and a mesh's 170 and more stay apart); or CHOLMOD's factor,
///     as its analysis predicts it (cholmod_factor_bytes, in the lower bound too: the analysis is
///     exact);
///   the integrator's vectors: kIntegratorVectors of `unknowns` doubles.
/// `lower_bound` takes the factors as no larger than the Newton matrix (L and U hold at least its
/// nonzeros) and held once, which no run goes below.
struct MemoryEstimate {
  double bytes = 0;
  double lower_bound = 0;
  double newton_nonzeros = 0;
  double factor_entries = 0;
  bool cholmod = false;  ///< factor_entries are CHOLMOD's L, not KLU's L and U
};
[[nodiscard]] MemoryEstimate integration_memory_estimate(const ModelSizes& model,
                                                         const IntegratedSizes& system);

/// The least any scheme holds for this model, before a scheme is chosen (the builder's refusal,
/// a Matrix Market size line): the model's matrices, and the integrator's vectors and a Newton
/// matrix of its diagonal alone over the fewest unknowns a scheme has, 2(n − m) (elimination's
/// masters and their velocities).
[[nodiscard]] MemoryEstimate least_memory_estimate(const ModelSizes& model);

/// The entries of L and U from which the Newton solvers keep a second copy of them, in the order
/// the triangular solves read them (KluSettings::streamed_solve_from,
/// dae/linsolve/fixed_pattern_klu.hpp).
constexpr long kStreamedSolveFromEntries = 200'000;
/// ... and the most flops their factorization may cost per entry for the copy to be kept
/// (KluSettings::streamed_solve_most_flops_per_entry). Beyond, the factorizations outweigh the
/// solves that would read the copy: a strip's banded factor costs about 8 to 12 flops an entry,
/// a mesh's nested-dissection fill 170 to 250 (2D) and 1,000 to 1,600 (3D), where the copy
/// saved none and 8 % of the time and took the peak from 1.1 to 1.7 and from 1.0 to 1.8 times
/// the bare driver's (docs/benchmarks.md).
constexpr double kStreamedSolveMostFlopsPerEntry = 64.0;

/// Whether a factor of `entries` entries whose factorization costs `flops` (0: not known) gets
/// the streamed copy, under these thresholds.
[[nodiscard]] constexpr bool keeps_streamed_copy(
    double entries, double flops, double from = static_cast<double>(kStreamedSolveFromEntries),
    double most_flops_per_entry = kStreamedSolveMostFlopsPerEntry) {
  return entries >= from && flops <= most_flops_per_entry * entries;
}

/// The memory a run can have, in bytes: MemAvailable of /proc/meminfo plus what this process holds
/// already (RssAnon of /proc/self/status), since the estimates count the model it has read and
/// built; nothing when /proc/meminfo cannot be read.
[[nodiscard]] std::optional<double> available_memory_bytes();

/// "1.2 GB" style: bytes with a decimal unit, one decimal.
[[nodiscard]] std::string format_bytes(double bytes);

/// The refusal text when even the lower bound of `estimate` exceeds `available` bytes (nothing
/// when it may fit): "N DOFs and M constraints need at least X to integrate under WHAT (...),
/// more than the Y this machine has available (MemAvailable in /proc/meminfo) ...". `what` names
/// the system ("the GGL scheme", "any scheme"). A model between the lower bound and the estimate
/// is not refused: memory_warning says it may not fit.
[[nodiscard]] std::optional<std::string> memory_refusal(const ModelSizes& sizes,
                                                        const MemoryEstimate& estimate,
                                                        const std::string& what, double available);

/// "CHOLMOD's factor" or "KLU's factors": what `estimate.factor_entries` counts.
[[nodiscard]] std::string factor_name(const MemoryEstimate& estimate);

/// A warning when the estimate (not its lower bound) exceeds `available` bytes.
[[nodiscard]] std::optional<std::string> memory_warning(const MemoryEstimate& estimate,
                                                        const std::string& what, double available);

}  // namespace condyn
