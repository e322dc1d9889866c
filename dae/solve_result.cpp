#include "dae/solve_result.hpp"

#include <stdexcept>

namespace condyn {

RunFailure failure_of(const IntegrationError& e) {
  RunFailure f;
  f.kind = e.kind;
  f.message = e.what();
  f.in_loop = e.in_loop;
  f.t0 = e.t0;
  f.t_end = e.t_end;
  f.t_reached = e.t_reached;
  f.last_step = e.last_step;
  f.steps = e.steps;
  f.elapsed_seconds = e.elapsed_seconds;
  return f;
}

const SolveResult& succeeded(const SolveResult& result) {
  if (!result.ok()) throw std::runtime_error(result.failure->message);
  return result;
}

}  // namespace condyn
