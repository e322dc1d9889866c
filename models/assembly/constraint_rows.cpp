// Constraint rows: supports and [[constraint]] terms to rows of A, their right-hand sides, and
// the position_value of velocity rows.

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/assembly/model_builder.hpp"

namespace condyn {

/// A coefficient must carry information: a subnormal one has lost its precision (and its
/// square underflows to 0 in any row norm), and one below eps times the row's largest vanishes
/// in every sum a·u, so it only pretends that its DOF is constrained.
void ModelBuilder::check_coefficients(const ConstraintSpec& cs) const {
  double largest = 0.0;
  for (const auto& [name, a] : cs.terms) largest = std::max(largest, std::abs(a));
  for (std::size_t k = 0; k < cs.terms.size(); ++k) {
    const auto& [name, a] = cs.terms[k];
    const SourcePoint key{cs.where.path + ".terms." + name,
                          line_of(cs.term_lines, k, cs.where.line)};
    if (a != 0.0 && std::abs(a) < std::numeric_limits<double>::min()) {
      fail(key, "the coefficient " + fmt(a) +
                    " is subnormal (below 2.2e-308): it has lost its precision; rescale the "
                    "constraint or remove the term");
    }
    if (a != 0.0 && std::abs(a) < std::numeric_limits<double>::epsilon() * largest) {
      fail(key, "the coefficient " + fmt(a) + " is below the roundoff of the row's largest (" +
                    fmt(largest) +
                    "): it changes no sum a·u, so the term only seems to constrain '" + name +
                    "'; remove it or rescale");
    }
  }
}

/// A table is piecewise linear: a constraint right-hand side needs derivatives it does not have
/// (docs/scenes.md, "Tabulated time functions").
void ModelBuilder::refuse_table_rhs(const TimeFunction& f, const SourcePoint& where,
                                    bool velocity_level) const {
  if (!f.has_table()) return;
  if (velocity_level) {
    fail(where,
         "a table cannot be a prescribed velocity: every scheme needs its integral and its "
         "derivative, and a piecewise linear record has a jumping derivative (an impulsive "
         "reaction at each sample); drive the structure by its ground acceleration with "
         "[ground_motion] (motion relative to the ground), or give a smooth function");
  }
  fail(where,
       "a table cannot be a prescribed displacement: it is piecewise linear, so its velocity "
       "jumps at every sample and its acceleration is a train of impulses, which the constraint "
       "would pass on as unbounded reaction forces (index-1 and GGL need that second "
       "derivative); apply a recorded ground acceleration with [ground_motion] (motion relative "
       "to the ground), or prescribe a smooth function of time");
}

void ModelBuilder::build_constraints() {
  const int n = model_.dofs();
  std::vector<Eigen::Triplet<double>> trip;
  for (int node : spec_.model.supports) {  // a fixed support: every DOF of the node is zero
    for (int d = 0; d < spec_.model.dimension; ++d) {
      Constraint c;
      const int dof = (node - 1) * spec_.model.dimension + d;
      c.name = "fix_" + model_.dof_names[static_cast<std::size_t>(dof)];
      c.coefficients = {{dof, 1.0}};
      c.position_value = c.value;
      c.where = {"model.supports", spec_.model.where.line};
      const int row = static_cast<int>(model_.constraints.size());
      trip.emplace_back(row, c.coefficients.front().first, 1.0);
      model_.constraints.push_back(std::move(c));
    }
  }
  for (const auto& cs : spec_.constraints) {
    Constraint c;
    c.name = cs.name;
    c.level = cs.level;
    c.value = cs.value;
    c.where = cs.where;
    const SourcePoint value_at{cs.where.path + ".value", cs.where.line};
    for (std::size_t k = 0; k < cs.terms.size(); ++k) {
      const auto& [name, a] = cs.terms[k];
      const int d =
          dof(name, {cs.where.path + ".terms." + name, line_of(cs.term_lines, k, cs.where.line)});
      if (a != 0.0) c.coefficients.emplace_back(d, a);
    }
    check_coefficients(cs);
    std::sort(c.coefficients.begin(), c.coefficients.end());
    refuse_table_rhs(c.value, value_at, c.level == ConstraintSpec::Level::velocity);
    check_time_function(c.value, value_at);
    c.value = acting_in_run(c.value, value_at);
    for (double b : c.value.breakpoints()) {
      fail(value_at,
           std::string("a step at t = ") + fmt(b) + " > 0 would make the prescribed " +
               (c.level == ConstraintSpec::Level::position ? "displacement" : "velocity") +
               " jump (an infinite " +
               (c.level == ConstraintSpec::Level::position ? "velocity" : "acceleration") +
               "); use a smooth function or a step at t = 0");
    }
    if (c.level == ConstraintSpec::Level::position) {
      c.position_value = c.value;
    } else {
      double a_u0 = 0.0, size = 0.0;
      for (const auto& [d, a] : c.coefficients) {
        a_u0 += a * model_.u0[d];
        size += std::abs(a * model_.u0[d]);
      }
      if (!std::isfinite(size)) {
        fail(spec_.initial.given() ? spec_.initial.where : cs.where,
             "a·u(0) of constraint '" + c.name +
                 "' overflows the double range (coefficients times initial displacements)");
      }
      std::vector<TimeTerm> terms = c.value.antiderivative().terms();
      terms.push_back(TimeFunction::constant(a_u0).terms().front());
      c.position_value = TimeFunction(std::move(terms));
      // |∫₀ᵗ h| <= |A| t_end for a harmonic, |A| t_end exp(r t_end) for an exponential: an
      // amplitude near the double range overflows there.
      if (!std::isfinite(magnitude_bound(c.position_value, spec_.solve.t_end))) {
        fail(value_at,
             "integrating this velocity constraint's right-hand side from t = 0 gives " +
                 c.position_value.describe() +
                 ", which overflows the double range before t_end = " + fmt(spec_.solve.t_end));
      }
    }
    const int row = static_cast<int>(model_.constraints.size());
    for (const auto& [d, a] : c.coefficients) trip.emplace_back(row, d, a);
    model_.constraints.push_back(std::move(c));
  }
  append_constraint_blocks(trip);
  model_.A.resize(static_cast<int>(model_.constraints.size()), n);
  model_.A.setFromTriplets(trip.begin(), trip.end());
  model_.A.makeCompressed();
}

}  // namespace condyn
