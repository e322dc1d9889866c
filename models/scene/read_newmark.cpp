// [solve] step (the fixed step of the Newmark family, which without it controls its steps, and
// RATTLE's, which needs it) and the Newmark family's parameters (newmark, hht, generalized_alpha,
// and newmark_constraints, their constraint form): each value checked against the method's range
// of unconditional stability (models/core/newmark_parameters.hpp), refused with its file, line and
// key.

#include "models/scene/scene_readers.hpp"

#include <string>

namespace condyn {

namespace {

/// A number of the table `owner` at `key`, checked by `problem`; nothing when absent.
template <class Problem>
std::optional<double> checked(const TomlAccess& r, const toml::table& owner,
                              const std::string& path, const char* key, const Problem& problem) {
  const auto* n = owner.get(key);
  if (n == nullptr) return std::nullopt;
  const std::string key_path = TomlAccess::join(path, key);
  const double v = r.number(*n, key_path);
  if (const auto why = problem(v)) r.fail(*n, key_path, *why);
  return v;
}

/// generalized_alpha = { rho_inf } or { alpha_m, alpha_f, beta, gamma } (all four).
void read_generalized_alpha(const TomlAccess& r, const toml::node& node, NewmarkFamilySpec& f) {
  const std::string path = "solve.generalized_alpha";
  const auto& g = r.table(node, path);
  r.check_keys(g, path, {"rho_inf", "alpha_m", "alpha_f", "beta", "gamma"});
  f.rho_inf = checked(r, g, path, "rho_inf", rho_inf_problem);
  const auto any = [](double) -> std::optional<std::string> { return std::nullopt; };
  const auto am = checked(r, g, path, "alpha_m", any);
  const auto af = checked(r, g, path, "alpha_f", any);
  const auto beta = checked(r, g, path, "beta", any);
  const auto gamma = checked(r, g, path, "gamma", any);
  const int given =
      int(am.has_value()) + int(af.has_value()) + int(beta.has_value()) + int(gamma.has_value());
  if (given == 0) return;
  if (f.rho_inf) {
    r.fail(node, path,
           "give rho_inf or the four parameters alpha_m, alpha_f, beta, gamma, not both");
  }
  if (given < 4) {
    r.fail(node, path,
           "parameters given directly need all four: alpha_m, alpha_f, beta and gamma (or give "
           "rho_inf alone)");
  }
  const AlphaParameters p{*am, *af, *beta, *gamma};
  if (const auto why = alpha_direct_problem(p)) r.fail(node, path, *why);
  f.alpha_direct = p;
}

}  // namespace

void SceneReader::read_fixed_step(const toml::table& t, SolveSpec& solve) const {
  if (const auto* n = t.get("step")) {
    solve.step = positive(*n, "solve.step");
    solve.step_line = at(*n, "solve.step").line;
    if (*solve.step > solve.t_end) {
      fail(*n, "solve.step",
           "is larger than t_end = " + fmt(solve.t_end) + " (got " + fmt(*solve.step) + ")");
    }
  }
  // RATTLE without a step is refused by SolveSpec::validate, after the command line's flags: a
  // --step or a --scheme may supply or lift what the file lacks.
  NewmarkFamilySpec& f = solve.newmark_family;
  if (const auto* n = t.get("newmark")) {
    const auto& nm = table(*n, "solve.newmark");
    check_keys(nm, "solve.newmark", {"beta", "gamma"});
    f.newmark_gamma = checked(*this, nm, "solve.newmark", "gamma", newmark_gamma_problem);
    const double gamma = f.newmark_gamma.value_or(kDefaultNewmarkGamma);
    const auto beta_problem = [gamma](double beta) { return newmark_beta_problem(beta, gamma); };
    f.newmark_beta = checked(*this, nm, "solve.newmark", "beta", beta_problem);
    // A γ given alone meets the default β: the key to change is γ.
    if (!f.newmark_beta) {
      if (const auto why = newmark_beta_problem(kDefaultNewmarkBeta, gamma)) {
        fail(*nm.get("gamma"), "solve.newmark.gamma",
             "needs beta >= gamma/2 = " + fmt(0.5 * gamma) + ", above the default beta = " +
                 fmt(kDefaultNewmarkBeta) + ": give [solve] newmark.beta too");
      }
    }
  }
  if (const auto* n = t.get("hht")) {
    const auto& h = table(*n, "solve.hht");
    check_keys(h, "solve.hht", {"alpha"});
    f.hht_alpha = checked(*this, h, "solve.hht", "alpha", hht_alpha_problem);
  }
  if (const auto* n = t.get("generalized_alpha")) read_generalized_alpha(*this, *n, f);
  if (const auto* n = t.get("newmark_constraints")) {
    const std::string s = string(*n, "solve.newmark_constraints");
    const auto form = newmark_constraints_from_string(s);
    if (!form) {
      fail(*n, "solve.newmark_constraints",
           "expected 'index3' (positions and multipliers, the default) or 'stabilized' (the "
           "velocity constraints too, index 2) (got '" +
               s + "')");
    }
    f.constraints = *form;
  }
}

}  // namespace condyn
