#include "models/core/newmark_parameters.hpp"

#include "models/core/number_cell.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace condyn {

const char* to_string(NewmarkConstraints form) {
  return form == NewmarkConstraints::stabilized ? "stabilized" : "index3";
}

std::optional<NewmarkConstraints> newmark_constraints_from_string(std::string_view s) {
  for (const auto form : {NewmarkConstraints::index3, NewmarkConstraints::stabilized}) {
    if (s == to_string(form)) return form;
  }
  return std::nullopt;
}

AlphaParameters newmark_parameters(double beta, double gamma) { return {0.0, 0.0, beta, gamma}; }

AlphaParameters hht_parameters(double alpha) {
  return {0.0, -alpha, 0.25 * (1.0 - alpha) * (1.0 - alpha), 0.5 - alpha};
}

AlphaParameters generalized_alpha_parameters(double rho_inf) {
  const double am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
  const double af = rho_inf / (rho_inf + 1.0);
  return {am, af, 0.25 * (1.0 - am + af) * (1.0 - am + af), 0.5 - am + af};
}

AlphaParameters alpha_parameters(Scheme scheme, const NewmarkFamilySpec& spec) {
  switch (scheme) {
    case Scheme::newmark:
      return newmark_parameters(spec.newmark_beta.value_or(kDefaultNewmarkBeta),
                                spec.newmark_gamma.value_or(kDefaultNewmarkGamma));
    case Scheme::hht:
      return hht_parameters(spec.hht_alpha.value_or(kDefaultHhtAlpha));
    case Scheme::generalized_alpha:
      if (spec.alpha_direct) return *spec.alpha_direct;
      return generalized_alpha_parameters(spec.rho_inf.value_or(kDefaultRhoInf));
    default:
      break;
  }
  throw std::invalid_argument(std::string("alpha_parameters: ") + to_string(scheme) +
                              " is not of the Newmark family");
}

std::optional<std::string> newmark_beta_problem(double beta, double gamma) {
  if (std::isfinite(beta) && beta >= 0.5 * gamma) return std::nullopt;
  return "must be >= gamma/2 = " + shortest_number(0.5 * gamma) +
         " for unconditional stability (below it, as linear acceleration beta = 1/6 or the "
         "central difference beta = 0, the method is stable only for h omega < "
         "1/sqrt(gamma/2 - beta); got " +
         shortest_number(beta) + ")";
}

std::optional<std::string> newmark_gamma_problem(double gamma) {
  if (std::isfinite(gamma) && gamma >= 0.5 && gamma <= 1.0) return std::nullopt;
  return "must lie in [0.5, 1]: below 0.5 the method amplifies every mode (negative numerical "
         "damping), above 1 it damps the low modes at first order (got " +
         shortest_number(gamma) + ")";
}

std::optional<std::string> hht_alpha_problem(double alpha) {
  if (std::isfinite(alpha) && alpha >= -1.0 / 3.0 && alpha <= 0.0) return std::nullopt;
  return "must lie in [-1/3, 0], where HHT-alpha is unconditionally stable and second-order "
         "accurate (got " +
         shortest_number(alpha) + ")";
}

std::optional<std::string> rho_inf_problem(double rho_inf) {
  if (std::isfinite(rho_inf) && rho_inf >= 0.0 && rho_inf <= 1.0) return std::nullopt;
  return "must lie in [0, 1]: it is the spectral radius of the step at infinite frequency "
         "(got " +
         shortest_number(rho_inf) + ")";
}

std::optional<std::string> alpha_direct_problem(const AlphaParameters& p) {
  const bool finite = std::isfinite(p.alpha_m) && std::isfinite(p.alpha_f) &&
                      std::isfinite(p.beta) && std::isfinite(p.gamma);
  if (!finite) return "every parameter must be a finite number";
  if (!(p.alpha_m <= p.alpha_f && p.alpha_f <= 0.5)) {
    return "needs alpha_m <= alpha_f <= 0.5 for unconditional stability (Chung and Hulbert "
           "1993; got alpha_m = " +
           shortest_number(p.alpha_m) + ", alpha_f = " + shortest_number(p.alpha_f) + ")";
  }
  // Roundoff of the formulas that give β and γ from ρ∞, whose results a user may paste.
  constexpr double kSlack = 1e-12;
  if (p.beta < 0.25 + 0.5 * (p.alpha_f - p.alpha_m) - kSlack) {
    return "beta must be >= 1/4 + (alpha_f - alpha_m)/2 = " +
           shortest_number(0.25 + 0.5 * (p.alpha_f - p.alpha_m)) +
           " for unconditional stability (got " + shortest_number(p.beta) + ")";
  }
  if (p.gamma < 0.5 - p.alpha_m + p.alpha_f - kSlack) {
    return "gamma must be >= 1/2 - alpha_m + alpha_f = " +
           shortest_number(0.5 - p.alpha_m + p.alpha_f) +
           " (equal: second order; below: the method "
           "amplifies; got " +
           shortest_number(p.gamma) + ")";
  }
  return std::nullopt;
}

bool damps_high_frequencies(const AlphaParameters& p) {
  // Chung and Hulbert's parameters put the damping in γ − ½ + αf − αm: zero for the
  // non-dissipative members, whatever αm = αf is (rounding of ρ∞ = 1's ½ and ½ stays far below).
  constexpr double kRounding = 1e-12;
  return (p.gamma - 0.5) + (p.alpha_f - p.alpha_m) > kRounding;
}

std::string describe(Scheme scheme, const AlphaParameters& p) {
  std::ostringstream s;
  s << to_string(scheme) << ": alpha_m = " << p.alpha_m << ", alpha_f = " << p.alpha_f
    << ", beta = " << p.beta << ", gamma = " << p.gamma;
  return s.str();
}

}  // namespace condyn
