#include "dae/solve.hpp"

#include <stdexcept>

#include "dae/elimination.hpp"

namespace condyn {

SchemeChoice choose_scheme(const Model& model, Scheme requested) {
  if (requested != Scheme::automatic) return {requested, "requested"};
  // Every constraint condyn reads today is linear with constant coefficients, hence holonomic or
  // integrable: elimination solves the smallest system (n − m DOFs, no multipliers).
  if (model.constraint_count() == 0) {
    return {Scheme::elimination, "no constraints: the model is integrated as it is"};
  }
  return {Scheme::elimination,
          "every constraint is linear and integrable: elimination solves the smallest system"};
}

IntegratorOptions integrator_options(const Model& model) {
  IntegratorOptions o;
  o.rtol = model.solve.rtol;
  o.atol = model.solve.atol;
  o.dense_linear_solver = model.solve.dense_linear_solver;
  o.output_times = model.output_times();
  o.breakpoints = model.breakpoints();
  return o;
}

Trajectory solve(const Model& model, Scheme scheme, const IntegratorOptions& options,
                 SolveSummary& summary) {
  switch (scheme) {
    case Scheme::elimination:
      return solve_elimination(model, options, summary);
    case Scheme::automatic:
      return solve(model, choose_scheme(model, scheme).scheme, options, summary);
    default:
      throw std::invalid_argument(std::string("scheme '") + to_string(scheme) +
                                  "' is not available in this build yet (the multiplier "
                                  "formulations are being written); use 'elimination' or 'auto'");
  }
}

}  // namespace condyn
