// Per-scheme memory estimates (dae/run/scheme_memory.hpp).

#include "dae/run/scheme_memory.hpp"

#include <stdexcept>

#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "dae/linsolve/kkt.hpp"
#include "models/core/source_point.hpp"

namespace condyn {

MemoryEstimate SchemeMemory::operator()(const SystemSize& size,
                                        const FactorizationChoice& factorization) {
  if (!condensed_factor_) {
    // The union of the patterns of M, C and K, whatever the scalars the Newton matrix weighs
    // them with (a sum keeps every stored entry).
    Eigen::SparseMatrix<double> S = model_.M + *model_.K;
    if (model_.has_damping()) S += model_.C;
    condensed_factor_ =
        predicted_klu_factor(model_.constraint_count() > 0 ? kkt_matrix(S, model_.A) : S);
  }
  IntegratedSizes sizes;
  sizes.unknowns = size.unknowns;
  sizes.newton_nonzeros = static_cast<double>(size.jacobian_nonzeros);
  sizes.factor_entries = size.condensed ? condensed_factor_->entries
                                        : sizes.newton_nonzeros + condensed_factor_->entries;
  sizes.factor_flops = condensed_factor_->flops;
  if (factorization.cholmod) {
    sizes.factor_entries = factorization.factor_entries;
    sizes.cholmod_factor_bytes = factorization.factor_bytes;
  }
  sizes.dense = size.dense;
  sizes.condensed = size.condensed;
  sizes.reduced = size.reduced;
  return integration_memory_estimate(model_sizes(model_), sizes);
}

std::optional<RunMemory> run_memory_estimate(const RunPlan& plan, SchemeDecisions& decisions) {
  if (plan.refusal) return std::nullopt;  // execute() refuses the scheme, and says why
  try {
    const SystemSize size = decisions.size_as(plan.scheme, plan.settings);
    return RunMemory{plan.scheme, SchemeMemory(*plan.model)(size, plan.factorization)};
  } catch (const std::invalid_argument&) {
    return std::nullopt;  // the scheme cannot be set up for the model: execute() says why
  }
}

std::optional<RunMemory> run_memory_estimate(const Model& model, const SolveSpec& settings) {
  SchemeDecisions decisions(model);
  try {
    return run_memory_estimate(plan(model, settings, decisions), decisions);
  } catch (const std::invalid_argument&) {
    return std::nullopt;  // plan() refuses the settings, and says why
  }
}

std::optional<std::string> check_run_memory(const RunPlan& plan, SchemeDecisions& decisions) {
  const std::optional<double> available = available_memory_bytes();
  if (!available) return std::nullopt;
  const std::optional<RunMemory> run = run_memory_estimate(plan, decisions);
  if (!run) return std::nullopt;
  const Model& model = *plan.model;
  const std::string what = "scheme " + std::string(to_string(run->scheme));
  if (const auto refusal = memory_refusal(model_sizes(model), run->estimate, what, *available)) {
    throw SceneError(scene_message(model.file, plan.settings.scheme_where, *refusal));
  }
  return memory_warning(run->estimate, what, *available);
}

}  // namespace condyn
