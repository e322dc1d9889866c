#include "dae/run/solve.hpp"

namespace condyn {

SolveResult solve(const Model& model, const SolveSpec& settings, const RunHooks& hooks) {
  return execute(plan(model, settings), hooks);
}

}  // namespace condyn
