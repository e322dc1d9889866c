#pragma once
/// A run in one call, for callers that need nothing between planning and running (the validation
/// suite, compare, check, Python): plan, then execute (dae/run/run_plan.hpp).

#include "dae/run/run_plan.hpp"
#include "dae/run/scheme_choice.hpp"
#include "dae/run/solve_result.hpp"
#include "models/core/model.hpp"
#include "models/core/output_quantity.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

/// execute(plan(model, settings), hooks): solves the model under settings.scheme (`automatic`
/// resolves through choose_scheme) with the run's settings (tolerances, budgets, times, scheme
/// parameters). A run that fails returns its failure as data (SolveResult::failure, with a
/// suggestion) and the rows computed before it. Throws SchemeNotApplicable for a scheme that
/// cannot treat the model, std::invalid_argument for settings that fail SolveSpec::validate(),
/// and std::exception when the scheme cannot be set up for the model (a singular reduced mass,
/// say).
[[nodiscard]] SolveResult solve(const Model& model, const SolveSpec& settings,
                                const RunHooks& hooks = {});

}  // namespace condyn
