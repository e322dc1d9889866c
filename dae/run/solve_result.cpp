#include "dae/run/solve_result.hpp"

#include <sstream>
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

std::string describe_failure(const SolveResult& result, double t_end) {
  const RunFailure& f = *result.failure;
  std::ostringstream s;
  s << "under " << to_string(result.scheme) << " (" << to_string(f.kind) << "): " << f.message;
  if (f.in_loop) {
    s << "\n  reached t = " << f.t_reached << " of t_end = " << t_end << ", last successful step "
      << f.last_step;
  }
  if (!f.suggestion.empty()) s << "\n  suggestion: " << f.suggestion;
  return s.str();
}

}  // namespace condyn
