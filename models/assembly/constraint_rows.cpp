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

/// A displacement record prescribes a displacement (position level only), and holds still
/// outside its samples: a run that goes beyond them needs the record at rest at that end, or its
/// velocity or acceleration would jump there (docs/scenes.md, "Support motion").
void ModelBuilder::check_record_rhs(const TimeFunction& f, const SourcePoint& where,
                                    bool velocity_level) const {
  if (!f.has_record()) return;
  if (velocity_level) {
    fail(where,
         "a displacement record prescribes a displacement: it is the right-hand side of a "
         "position-level constraint (level = \"position\", the default), not of a velocity one");
  }
  // Roundoff of the record's own peaks: a record that ends at rest ends there to a few ulps.
  constexpr double kAtRest = 1e-12;
  for (const auto& term : f.terms()) {
    if (term.kind != TimeTerm::Kind::record) continue;
    const KinematicRecord& r = *term.record;
    auto moving = [&](std::size_t k) {
      return std::abs(r.velocity[k]) > kAtRest * r.bound[1] ||
             std::abs(r.acceleration[k]) > kAtRest * r.bound[2];
    };
    auto refuse = [&](std::size_t k, const std::string& when) {
      fail(where, term.describe() + " " + when + " while moving (velocity " +
                      fmt(term.amplitude * r.velocity[k]) + ", acceleration " +
                      fmt(term.amplitude * r.acceleration[k]) +
                      " at that sample): outside its samples a record holds still, so the "
                      "support's velocity or acceleration would jump there (an unbounded or "
                      "jumping reaction); give samples over the whole run, ending at rest, or "
                      "end the run with the record");
    };
    if (r.times.front() > 0.0 && moving(0)) {
      refuse(0, "starts at t = " + fmt(r.times.front()) + ", after t = 0,");
    }
    if (r.times.back() < spec_.solve.t_end && moving(r.samples() - 1)) {
      refuse(r.samples() - 1, "ends at t = " + fmt(r.times.back()) +
                                  ", before t_end = " + fmt(spec_.solve.t_end) + ",");
    }
  }
}

/// A table is piecewise linear: a constraint right-hand side needs derivatives it does not have
/// (docs/scenes.md, "Tabulated time functions").
void ModelBuilder::refuse_table_rhs(const TimeFunction& f, const SourcePoint& where,
                                    bool velocity_level) const {
  check_record_rhs(f, where, velocity_level);
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
       "derivative); give the record as { type = \"displacement_record\", … } with its velocity "
       "and acceleration, or its acceleration alone (integrated twice), or apply a recorded "
       "ground acceleration with [ground_motion] (motion relative to the ground)");
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
    check_time_function(c.value, value_at, true);
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
