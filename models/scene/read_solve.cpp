#include "models/scene/scene_readers.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace condyn {

namespace {

/// solve.t_end and solve.output_step.
void read_horizon(const TomlAccess& r, const toml::table& t, const std::string& path,
                  SolveSpec& solve) {
  solve.t_end = r.positive(r.required(t, path, "t_end"), "solve.t_end");
  // IDA tests its stop time by the product (t_stop - t) h with a first step h of at most
  // t_end / 1000: below about 1e-160 it underflows to 0 and the run is refused at t = 0 as
  // 'tstop is behind current t'.
  if (solve.t_end < 1e-150) {
    r.fail(*t.get("t_end"), "solve.t_end",
           TomlAccess::fmt(solve.t_end) +
               " is below 1e-150, where the integrator's products of times and steps underflow: "
               "express time in a smaller unit");
  }
  solve.output_step = r.positive(r.required(t, path, "output_step"), "solve.output_step");
  solve.output_step_line = r.at(*t.get("output_step"), "solve.output_step").line;
}

/// The step budgets, the BDF order and the wall-time budget.
void read_budgets(const TomlAccess& r, const toml::table& t, const std::string& path,
                  SolveSpec& solve) {
  // Step budgets: whole numbers >= 1 (1e6 is accepted: a budget is often written so).
  const auto steps = [&](const char* key) -> std::optional<long> {
    const auto* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    const std::string key_path = TomlAccess::join(path, key);
    const double v = r.number(*n, key_path);
    if (!(v >= 1.0) || v != std::floor(v) || v > 1e18) {
      r.fail(*n, key_path, "must be a whole number of steps >= 1 (got " + TomlAccess::fmt(v) + ")");
    }
    return static_cast<long>(v);
  };
  if (const auto v = steps("max_steps")) solve.max_steps = *v;
  if (const auto v = steps("max_steps_per_output")) solve.max_steps_per_output = *v;
  if (const auto* n = t.get("max_order")) {
    const double v = r.number(*n, "solve.max_order");
    if (!(v >= 1.0 && v <= 5.0) || v != std::floor(v)) {
      r.fail(*n, "solve.max_order",
             "must be a whole number from 1 to 5, the BDF orders IDA and CVODE offer (got " +
                 TomlAccess::fmt(v) + ")");
    }
    solve.max_order = static_cast<int>(v);
  }
  if (const auto* n = t.get("bridge_singular")) {
    const auto* b = n->as_boolean();
    if (b == nullptr) r.fail(*n, "solve.bridge_singular", "expected true or false");
    solve.bridge_singular = b->get();
  }
  if (const auto* n = t.get("max_wall_time"))
    solve.max_wall_time = r.positive(*n, "solve.max_wall_time");
}

/// rtol and the absolute tolerances.
void read_tolerances(const TomlAccess& r, const toml::table& t, SolveSpec& solve) {
  if (const auto* n = t.get("rtol")) {
    solve.rtol = r.positive(*n, "solve.rtol");
    if (solve.rtol < kMinRtol || solve.rtol >= 1.0) {
      r.fail(*n, "solve.rtol",
             "is out of range: a relative tolerance lies in [" + TomlAccess::fmt(kMinRtol) +
                 ", 1) (got " + TomlAccess::fmt(solve.rtol) + ")");
    }
  }
  const auto atol_at = [&](const toml::node& n, const std::string& key) {
    const double v = r.positive(n, key);
    if (v < kMinAtol) {
      r.fail(n, key,
             "is too small: an absolute tolerance below " + TomlAccess::fmt(kMinAtol) +
                 " gives error weights the integrator cannot hold in double precision (got " +
                 TomlAccess::fmt(v) + ")");
    }
    return v;
  };
  if (const auto* n = t.get("atol")) solve.atol = atol_at(*n, "solve.atol");
  if (const auto* n = t.get("atol_velocity"))
    solve.atol_velocity = atol_at(*n, "solve.atol_velocity");
  if (const auto* n = t.get("atol_multiplier"))
    solve.atol_multiplier = atol_at(*n, "solve.atol_multiplier");
  if (const auto* n = t.get("atol_mu")) solve.atol_mu = atol_at(*n, "solve.atol_mu");
}

/// The gains of the Baumgarte and penalty schemes.
void read_gains(const TomlAccess& r, const toml::table& t, SolveSpec& solve) {
  if (const auto* n = t.get("baumgarte")) {
    const auto& b = r.table(*n, "solve.baumgarte");
    r.check_keys(b, "solve.baumgarte", {"alpha", "beta"});
    // The constraint forces carry 2α ψ and β² φ: gains whose terms leave the double range gave
    // NaN at t = 0 and a message about loads (β = 1e160).
    if (const auto* a = b.get("alpha")) {
      solve.baumgarte_alpha = r.positive(*a, "solve.baumgarte.alpha");
      if (*solve.baumgarte_alpha > 1e300) {
        r.fail(*a, "solve.baumgarte.alpha",
               "2 alpha overflows the double range: give at most 1e300");
      }
    }
    if (const auto* be = b.get("beta")) {
      solve.baumgarte_beta = r.positive(*be, "solve.baumgarte.beta");
      if (*solve.baumgarte_beta > 1e150) {
        r.fail(*be, "solve.baumgarte.beta",
               "beta^2 overflows the double range: give at most 1e150");
      }
    }
  }
  if (const auto* n = t.get("penalty")) {
    const auto& pt = r.table(*n, "solve.penalty");
    r.check_keys(pt, "solve.penalty", {"weight"});
    if (const auto* w = pt.get("weight"))
      solve.penalty_weight = r.positive(*w, "solve.penalty.weight");
  }
}

/// The slave DOFs of master-slave elimination.
void read_slaves(const TomlAccess& r, const toml::table& t, SolveSpec& solve) {
  if (const auto* n = t.get("slaves")) {
    const auto& arr = r.array(*n, "solve.slaves");
    if (arr.empty()) {
      r.fail(*n, "solve.slaves",
             "the list is empty; name one slave DOF per constraint, or leave the key out for the "
             "automatic choice");
    }
    for (std::size_t i = 0; i < arr.size(); ++i) {
      solve.slaves.push_back(r.string(*arr.get(i), TomlAccess::index("solve.slaves", i)));
      solve.slaves_lines.push_back(r.at(*arr.get(i), TomlAccess::index("solve.slaves", i)).line);
    }
  }
}

/// The choices of linear solver, Newton solve, constraint treatment and redundant rows.
void read_choices(const TomlAccess& r, const toml::table& t, SolveSpec& solve) {
  if (const auto* n = t.get("linear_solver")) {
    const std::string s = r.string(*n, "solve.linear_solver");
    if (s != "auto" && s != "klu" && s != "cholmod" && s != "dense") {
      r.fail(*n, "solve.linear_solver", "expected 'auto', 'klu', 'cholmod' or 'dense'");
    }
    solve.dense_linear_solver = s == "dense";
    using LinearSolver = SolveSpec::LinearSolver;
    solve.linear_solver = s == "klu"       ? LinearSolver::klu
                          : s == "cholmod" ? LinearSolver::cholmod
                                           : LinearSolver::automatic;
    solve.linear_solver_where = r.at(*n, "solve.linear_solver");
  }
  if (const auto* n = t.get("newton")) {
    const std::string s = r.string(*n, "solve.newton");
    if (s != "condensed" && s != "full") {
      r.fail(*n, "solve.newton", "expected 'full' or 'condensed'");
    }
    solve.condensed_newton = s == "condensed";
  }
  if (const auto* n = t.get("constraints")) {
    const std::string s = r.string(*n, "solve.constraints");
    if (s != "mixed" && s != "multipliers") {
      r.fail(*n, "solve.constraints", "expected 'mixed' or 'multipliers'");
    }
    solve.treatment =
        s == "mixed" ? SolveSpec::Treatment::mixed : SolveSpec::Treatment::multipliers;
    if (!mixes(solve.scheme)) {
      r.fail(*n, "solve.constraints", "'" + s + "' " + treatment_refusal(solve.scheme));
    }
  }
  if (const auto* n = t.get("redundant")) {
    const std::string s = r.string(*n, "solve.redundant");
    if (s != "refuse" && s != "drop") r.fail(*n, "solve.redundant", "expected 'refuse' or 'drop'");
    solve.drop_redundant = s == "drop";
  }
}

}  // namespace

void SceneReader::read_solve(const toml::node& node, SolveSpec& solve) const {
  const std::string path = "solve";
  const auto& t = table(node, path);
  solve.where = at(node, path);
  check_keys(t, path,
             {"t_end",
              "output_step",
              "scheme",
              "rtol",
              "atol",
              "atol_velocity",
              "atol_multiplier",
              "atol_mu",
              "baumgarte",
              "penalty",
              "slaves",
              "linear_solver",
              "newton",
              "redundant",
              "max_steps",
              "max_wall_time",
              "constraints",
              "max_order",
              "bridge_singular",
              "max_steps_per_output",
              "step",
              "newmark",
              "hht",
              "generalized_alpha",
              "newmark_constraints"});
  read_horizon(*this, t, path, solve);
  read_budgets(*this, t, path, solve);
  if (const auto* n = t.get("scheme")) {
    solve.scheme = parse_scheme(*n, "solve.scheme");
    solve.scheme_where = at(*n, "solve.scheme");
  }
  read_fixed_step(t, solve);
  read_tolerances(*this, t, solve);
  read_gains(*this, t, solve);
  read_slaves(*this, t, solve);
  read_choices(*this, t, solve);
}

Scheme SceneReader::parse_scheme(const toml::node& node, const std::string& path) const {
  const std::string s = string(node, path);
  if (const auto scheme = scheme_from_string(s)) return *scheme;
  fail(node, path, "unknown scheme '" + s + "' (expected " + scheme_names() + ")");
}

}  // namespace condyn
