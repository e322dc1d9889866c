#pragma once
/// The memory a run holds under each scheme, estimated before any solver work from the size of
/// the system the scheme integrates (dae/run/solve.hpp's SystemSize) and the entries of its Newton
/// matrix's KLU factors predicted by one symbolic analysis (models/core/memory_estimate.hpp for the
/// sum); `info` prints it per scheme and `run` checks the chosen scheme's against the machine's
/// available memory.

#include <optional>
#include <string>

#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "dae/run/run_plan.hpp"
#include "dae/run/scheme_choice.hpp"
#include "models/core/memory_estimate.hpp"

namespace condyn {

/// Estimates for many schemes of one model (`info`'s table): the analysis is made once.
///
/// The factor's entries: KLU's analysis under AMD (predicted_klu_factor) of the condensed
/// matrix [M + C + K, Aᵀ; A, 0] of the model, F_c. A condensed Newton matrix (the projection's
/// saddle point, [solve] newton = "condensed") factors to F_c. The integrator's Jacobian over
/// [u; v; ...] (J nonzeros) factors to J + F_c: its rows u' − v pair each position with its
/// velocity, and eliminating the positions puts their columns into L and U and leaves the
/// condensed matrix, so F_c is analysed rather than the Jacobian itself, whose A + Aᵀ pattern
/// the analysis would count about twice (the benchmark lattice at 10⁴ DOFs: 822,704 predicted
/// for index1's Jacobian against 457,260 factored; J + F_c = 459,049). Elimination, the mixed
/// treatment and penalty factor a matrix of the same structure over fewer or as many DOFs: the
/// model's F_c bounds theirs. The analysis costs a fraction of one factorization. Its flops,
/// which the Jacobian's factorization shares (the positions' columns cost a few each), decide
/// whether the factors' streamed copy is counted (keeps_streamed_copy).
class SchemeMemory {
 public:
  explicit SchemeMemory(const Model& model) : model_(model) {}
  /// The estimate for a run that integrates a system of this size, its Newton matrix factored as
  /// `factorization` chose (CHOLMOD's predicted factor in place of KLU's when it chose CHOLMOD).
  [[nodiscard]] MemoryEstimate operator()(const SystemSize& size,
                                          const FactorizationChoice& factorization = {});

 private:
  const Model& model_;
  std::optional<KluFactorPrediction> condensed_factor_;  ///< F_c, analysed at the first call
};

/// The scheme a run of `plan` integrates and its estimate, sized with `decisions` (those the plan
/// was made with, so nothing is decided twice), or nothing when the scheme cannot be sized
/// (execute() then says why).
struct RunMemory {
  Scheme scheme = Scheme::ggl;
  MemoryEstimate estimate;
};
[[nodiscard]] std::optional<RunMemory> run_memory_estimate(const RunPlan& plan,
                                                           SchemeDecisions& decisions);
/// The same for a run of `model` under `settings`, planned here; nothing when plan() refuses the
/// settings.
[[nodiscard]] std::optional<RunMemory> run_memory_estimate(const Model& model,
                                                           const SolveSpec& settings);

/// What a run of `plan` is told before it starts: throws SceneError when even the lower bound of
/// its scheme's estimate exceeds the available memory (`where` the scheme's source, as
/// memory_refusal says), and returns memory_warning's text when the estimate does; nothing when
/// it fits, when /proc/meminfo cannot be read, or when the scheme cannot be sized.
[[nodiscard]] std::optional<std::string> check_run_memory(const RunPlan& plan,
                                                          SchemeDecisions& decisions);

}  // namespace condyn
