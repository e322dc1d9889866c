// SolveSpec's behaviour: the run settings checked on their own (the parser checks them with file
// and line; callers that set them in code, such as compare's tolerance sweep and the Python
// module, get the same rules here) and the output times they ask for.

#include "models/core/solve_spec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "models/core/time_roundoff.hpp"

namespace condyn {

namespace {

std::string text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

void require(bool ok, const std::string& key, const std::string& what, double got) {
  if (!ok) throw std::invalid_argument("solve." + key + " " + what + " (got " + text(got) + ")");
}

void require_positive(double v, const std::string& key) {
  require(std::isfinite(v) && v > 0.0, key, "must be a finite number > 0", v);
}

void require_atol(double v, const std::string& key) {
  require_positive(v, key);
  require(v >= kMinAtol, key, "must be at least " + text(kMinAtol), v);
}

/// The fixed-step schemes' settings: a step in (0, t_end] when given (the others ignore it; without
/// it the Newmark family's steps are error-controlled, and RATTLE is refused), and the Newmark
/// family's parameters in range (models/core/newmark_parameters.hpp).
void validate_fixed_step(const SolveSpec& s) {
  if (s.step) {
    require_positive(*s.step, "step");
    require(*s.step <= s.t_end, "step", "must be at most t_end = " + text(s.t_end), *s.step);
  } else if (s.scheme == Scheme::rattle) {
    throw std::invalid_argument(std::string("solve.step: the ") + to_string(s.scheme) +
                                " scheme runs with a fixed step: give [solve] step (or --step)");
  }
  const NewmarkFamilySpec& f = s.newmark_family;
  const auto check = [](const std::optional<std::string>& problem, const char* key) {
    if (problem) throw std::invalid_argument(std::string("solve.") + key + " " + *problem);
  };
  if (f.newmark_gamma) check(newmark_gamma_problem(*f.newmark_gamma), "newmark.gamma");
  const double gamma = f.newmark_gamma.value_or(kDefaultNewmarkGamma);
  // β unset is the default β, which a large γ may leave below γ/2.
  check(newmark_beta_problem(f.newmark_beta.value_or(kDefaultNewmarkBeta), gamma), "newmark.beta");
  if (f.hht_alpha) check(hht_alpha_problem(*f.hht_alpha), "hht.alpha");
  if (f.rho_inf) check(rho_inf_problem(*f.rho_inf), "generalized_alpha.rho_inf");
  if (f.alpha_direct) check(alpha_direct_problem(*f.alpha_direct), "generalized_alpha");
}

}  // namespace

void SolveSpec::validate() const {
  require_positive(t_end, "t_end");
  require_positive(output_step, "output_step");
  require(std::isfinite(rtol) && rtol >= kMinRtol && rtol < 1.0, "rtol",
          "must lie in [" + text(kMinRtol) + ", 1)", rtol);
  require_atol(atol, "atol");
  if (atol_velocity) require_atol(*atol_velocity, "atol_velocity");
  if (atol_multiplier) require_atol(*atol_multiplier, "atol_multiplier");
  if (atol_mu) require_atol(*atol_mu, "atol_mu");
  if (baumgarte_alpha) require_positive(*baumgarte_alpha, "baumgarte.alpha");
  if (baumgarte_beta) require_positive(*baumgarte_beta, "baumgarte.beta");
  if (penalty_weight) require_positive(*penalty_weight, "penalty.weight");
  require(max_order >= 1 && max_order <= 5, "max_order", "must be a whole number from 1 to 5",
          static_cast<double>(max_order));
  require(max_steps >= 0, "max_steps", "must be >= 0 (0: no budget)",
          static_cast<double>(max_steps));
  require(std::isfinite(max_wall_time) && max_wall_time >= 0.0, "max_wall_time",
          "must be a finite number >= 0 (0: no budget)", max_wall_time);
  require(max_steps_per_output >= 0, "max_steps_per_output", "must be >= 0 (0: the default budget)",
          static_cast<double>(max_steps_per_output));
  validate_fixed_step(*this);
}

long SolveSpec::steps_per_output_budget() const {
  if (max_steps_per_output > 0) return max_steps_per_output;
  return std::max(kDefaultStepsPerOutput, max_steps);
}

std::string SolveSpec::override_scheme(Scheme s, SourcePoint chosen_at) {
  scheme = s;
  scheme_where = std::move(chosen_at);
  if (treatment == Treatment::automatic || mixes(s)) return {};
  const char* name = treatment == Treatment::mixed ? "mixed" : "multipliers";
  treatment = Treatment::automatic;
  return std::string("[solve] constraints = \"") + name + "\" is set aside: it " +
         treatment_refusal(s);
}

namespace {

/// Whether k·output_step is t_end or beyond, up to the time axis' roundoff.
bool at_or_past_end(const SolveSpec& s, long k) {
  return static_cast<double>(k) * s.output_step > s.t_end - time_merge_tolerance(0.0, s.t_end);
}

}  // namespace

long SolveSpec::output_count() const {
  // The first multiple at or past t_end, from the quotient, then settled by the same test the
  // times use (the quotient's rounding can put it one off).
  const double q = std::floor(t_end / output_step);
  if (!(q < 1e15)) return std::numeric_limits<long>::max();  // far beyond any row limit
  auto k = static_cast<long>(q);
  while (k > 0 && at_or_past_end(*this, k - 1)) --k;
  while (!at_or_past_end(*this, k)) ++k;
  return k + 1;  // 0, h, ..., (k − 1) h and t_end
}

std::vector<double> SolveSpec::output_times() const {
  const long count = output_count();
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(count));
  for (long k = 0; k + 1 < count; ++k) times.push_back(static_cast<double>(k) * output_step);
  times.push_back(t_end);
  return times;
}

}  // namespace condyn
