#pragma once
/// What integrating a model will hold in memory, estimated from its sizes and nonzeros before any
/// solver work, and the refusal of a model that will not fit in the machine's available memory.

#include <optional>
#include <string>

namespace condyn {

/// Sizes the estimate is made from: DOFs n, constraints m, and the nonzeros of M, C, K and A.
struct ModelSizes {
  double dofs = 0, constraints = 0;
  double nnz_mass = 0, nnz_damping = 0, nnz_stiffness = 0, nnz_constraints = 0;
};

/// Bytes for the largest formulation (GGL: y = [u; v; λ; μ] of size N = 2n + 2m) with a KLU
/// factorization of its Newton matrix, whose nonzeros are those of cj²M + cjC + K blocks, the
/// identity couplings (2n) and A, Aᵀ twice (4 nnz(A)):
///   Jacobian and its pattern copy: 2 × 12 B per nonzero (value + row index);
///   KLU's L and U: kKluFillFactor × 12 B per nonzero of the Newton matrix, twice from
///   kStreamedSolveFromEntries entries on (the copy the solves stream);
///   IDA's vectors: 30 of length N (six history arrays, error weights, work vectors);
///   the model's own sparse matrices, held three times (Model, LinearSystem, evaluator).
/// `bytes` takes KLU's fill as kKluFillFactor; `lower_bound` as none at all (L and U hold at
/// least the Newton matrix's nonzeros, twice when that is kStreamedSolveFromEntries or more),
/// which no run can go below.
struct MemoryEstimate {
  double bytes = 0;
  double lower_bound = 0;
  double newton_nonzeros = 0;
};
[[nodiscard]] MemoryEstimate integration_memory_estimate(const ModelSizes& sizes);

/// KLU's fill is unknown until it factors. AMD-ordered matrices of 2D meshes fill like n log n,
/// 3 to 10 times their nonzeros up to a million unknowns; 20 leaves a margin for 3D meshes and
/// constraint rows. A model that needs more fails in KLU with an allocation error, not a crash.
constexpr double kKluFillFactor = 20.0;

/// The entries of L and U from which the Newton solvers keep a second copy of them, in the order
/// the triangular solves read them (KluSettings::streamed_solve_from, dae/fixed_pattern_klu.hpp).
constexpr long kStreamedSolveFromEntries = 200'000;

/// The memory a run can have, in bytes: MemAvailable of /proc/meminfo plus what this process holds
/// already (RssAnon of /proc/self/status), since the estimates count the model it has read and
/// built; nothing when /proc/meminfo cannot be read.
[[nodiscard]] std::optional<double> available_memory_bytes();

/// "about 1.2 GB" style: bytes with a binary-free decimal unit, two significant figures.
[[nodiscard]] std::string format_bytes(double bytes);

/// The refusal text when even the lower bound of `estimate` exceeds `available` bytes (nothing
/// when it may fit): "N DOFs and M constraints need at least X to integrate (...), more than the
/// Y this machine has available (MemAvailable in /proc/meminfo) ...". A model between the lower
/// bound and the estimate is not refused: memory_warning says it may not fit.
[[nodiscard]] std::optional<std::string> memory_refusal(const ModelSizes& sizes,
                                                        const MemoryEstimate& estimate,
                                                        double available);

/// A warning when the estimate (not its lower bound) exceeds `available` bytes.
[[nodiscard]] std::optional<std::string> memory_warning(const MemoryEstimate& estimate,
                                                        double available);

}  // namespace condyn
