// The initial state: u0 and v0 from [initial], their consistency with the constraints
// (kConsistencyTolerance), and [initial] project = true.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

#include "models/assembly/initial_projection.hpp"
#include "models/assembly/model_builder.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/linear_system.hpp"

namespace condyn {

void ModelBuilder::build_initial() {
  const int n = model_.dofs();
  model_.u0 = base_u0_.size() == n ? base_u0_ : Eigen::VectorXd::Zero(n);
  model_.v0 = base_v0_.size() == n ? base_v0_ : Eigen::VectorXd::Zero(n);
  const InitialSpec& in = spec_.initial;
  for (std::size_t k = 0; k < in.displacement.size(); ++k) {
    const auto& [name, value] = in.displacement[k];
    model_.u0[dof(name, {"initial.displacement." + name,
                         line_of(in.displacement_lines, k, in.where.line)})] = value;
  }
  for (std::size_t k = 0; k < in.velocity.size(); ++k) {
    const auto& [name, value] = in.velocity[k];
    model_
        .v0[dof(name, {"initial.velocity." + name, line_of(in.velocity_lines, k, in.where.line)})] =
        value;
  }
}

void ModelBuilder::check_initial_consistency() const {
  if (spec_.model.mechanism) {  // judged against the mechanism's size: multibody_start.cpp
    check_mechanism_start();
    return;
  }
  if (model_.is_nonlinear()) {
    check_nonlinear_consistency();
    return;
  }
  // Roundoff of the whole state: what a computed start ([initial] project = true, static = true)
  // leaves on a row whose own terms are 0 (2.4e-17 on a still DOF beside velocities of 1), far
  // below any value written by hand and meant.
  const double u_scale = model_.u0.size() > 0 ? model_.u0.cwiseAbs().maxCoeff() : 0.0;
  const double v_scale = model_.v0.size() > 0 ? model_.v0.cwiseAbs().maxCoeff() : 0.0;
  constexpr double kStateRoundoff = 64 * std::numeric_limits<double>::epsilon();
  for (const auto& c : model_.constraints) {
    double au = 0.0, av = 0.0, su = 0.0, sv = 0.0, a_sum = 0.0;
    for (const auto& [d, a] : c.coefficients) {
      au += a * model_.u0[d];
      av += a * model_.v0[d];
      su += std::abs(a * model_.u0[d]);
      sv += std::abs(a * model_.v0[d]);
      a_sum += std::abs(a);
    }
    const bool position = c.level == ConstraintSpec::Level::position;
    const std::string where = "constraint '" + c.name + "'";
    if (!std::isfinite(su) || !std::isfinite(sv)) {
      fail(spec_.initial.given() ? spec_.initial.where : c.where,
           "a·u(0) or a·v(0) of " + where +
               " overflows the double range (coefficients times initial values)");
    }
    // Negated comparisons: a NaN residual is a violation, never a pass.
    // Judged against the sizes of what is compared: a·u's terms and the right-hand side's
    // (TimeFunction::magnitude: a cosine drive's sin(π/2)-phase velocity is 1e-17, not 0).
    if (position) {
      const double g = c.value.value(0.0);
      const double size = std::max({su, std::abs(g), c.value.magnitude(0, 0.0), 1e-300});
      if (!(std::abs(au - g) <=
            std::max(kConsistencyTolerance * size, kStateRoundoff * a_sum * u_scale))) {
        fail(spec_.initial.given() ? spec_.initial.where : c.where,
             "initial displacements violate " + where + ": a·u(0) = " + fmt(au) +
                 " but the constraint requires " + fmt(g) + " (residual " +
                 computed_fmt(au - g, "a·u(0) and the required value") + ")");
      }
    }
    const double gv = position ? c.value.derivative(1, 0.0) : c.value.value(0.0);
    const double gv_size = c.value.magnitude(position ? 1 : 0, 0.0);
    if (!(std::abs(av - gv) <=
          std::max(kConsistencyTolerance * std::max({sv, std::abs(gv), gv_size, 1e-300}),
                   kStateRoundoff * a_sum * v_scale))) {
      fail(spec_.initial.given() ? spec_.initial.where : c.where,
           "initial velocities violate " + where + ": a·v(0) = " + fmt(av) +
               " but the constraint requires " + fmt(gv) + " (residual " +
               computed_fmt(av - gv, "a·v(0) and the required value") +
               "); set [initial] velocity to match");
    }
  }
}

/// The consistency check accepts a residual at the roundoff of the data: a drive 1e6 sin(t + π)
/// is 1.2e-10 at t = 0 (sin π is not 0 in doubles), beside u(0) = 0. GGL and index3 hold the
/// position rows to atol from their first step, and a residual above atol is an error no step
/// size cures: with atol 1e-12 they failed the error test at t = 0. u0 and v0 move by the
/// minimum-norm correction Aᵀ(A Aᵀ)⁻¹ r that meets the rows exactly (to roundoff): a change of
/// the size the check accepted, made only where a residual is not exactly 0.
void ModelBuilder::settle_initial_roundoff() {
  const int m = model_.constraint_count();
  if (m == 0 || model_.A.rows() != m) return;
  const Eigen::VectorXd au = model_.A * model_.u0, av = model_.A * model_.v0;
  Eigen::VectorXd ru(m), rv(m);
  bool any = false;
  for (int i = 0; i < m; ++i) {
    const auto& c = model_.constraints[static_cast<std::size_t>(i)];
    const bool position = c.level == ConstraintSpec::Level::position;
    ru[i] = position ? c.value.value(0.0) - au[i] : 0.0;
    rv[i] = (position ? c.value.derivative(1, 0.0) : c.value.value(0.0)) - av[i];
    any = any || ru[i] != 0.0 || rv[i] != 0.0;
  }
  if (!any) return;
  const Eigen::SparseMatrix<double> aat = model_.A * model_.A.transpose();
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(aat);
  if (ldlt.info() != Eigen::Success) return;  // dependent rows: left as the check accepted them
  const Eigen::VectorXd du = model_.A.transpose() * ldlt.solve(ru);
  const Eigen::VectorXd dv = model_.A.transpose() * ldlt.solve(rv);
  // Only a correction that meets the rows and is of the residual's size (rows that are nearly
  // dependent could make it large): else the start stays as the check accepted it.
  const double row_min = std::sqrt(aat.diagonal().minCoeff());
  const auto sound = [&](const Eigen::VectorXd& d, const Eigen::VectorXd& r) {
    const double size = r.cwiseAbs().maxCoeff();
    return d.allFinite() && (model_.A * d - r).cwiseAbs().maxCoeff() <= 1e-3 * size &&
           d.cwiseAbs().maxCoeff() <= 1e3 * size / row_min;
  };
  if (!(row_min > 0.0) || !sound(du, ru) || !sound(dv, rv)) return;
  model_.u0 += du;
  model_.v0 += dv;
}

/// φ(0, u0) and ψ(0, u0, v0) of a nonlinear model, relative to the size of the state.
void ModelBuilder::check_nonlinear_consistency() const {
  std::vector<int> all(static_cast<std::size_t>(model_.constraint_count()));
  std::iota(all.begin(), all.end(), 0);
  check_nonlinear_rows(all);
}

void ModelBuilder::check_nonlinear_rows(const std::vector<int>& rows) const {
  const auto evaluator = model_.evaluator();
  MechanicalSystem& s = *evaluator;
  const int m = s.constraints();
  Eigen::VectorXd phi(m), psi(m);
  s.position_residual(0.0, model_.u0, phi);
  s.velocity_residual(0.0, model_.u0, model_.v0, psi);
  const double u_scale = std::max(1.0, model_.u0.lpNorm<Eigen::Infinity>());
  const double v_scale = std::max(1.0, model_.v0.lpNorm<Eigen::Infinity>());
  for (const int i : rows) {
    const auto& c = model_.constraints[static_cast<std::size_t>(i)];
    const int r = system_row(i);
    // Negated comparisons: a NaN residual is a violation, never a pass.
    const bool bad_u = !(std::abs(phi[r]) <= kConsistencyTolerance * u_scale);
    const bool bad_v = !(std::abs(psi[r]) <= kConsistencyTolerance * v_scale * u_scale);
    if (!bad_u && !bad_v) continue;
    fail(spec_.initial.given() ? spec_.initial.where : c.where,
         std::string("initial ") + (bad_u ? "displacements" : "velocities") +
             " violate constraint '" + c.name + "'" +
             (c.nonlinear_kind.empty() ? "" : " (" + c.nonlinear_kind + ")") + ": residual " +
             computed_fmt(bad_u ? phi[r] : psi[r],
                          "products of the initial coordinates, lengths and velocities") +
             "; fix [initial], or set [initial] project = true to project the initial state "
             "onto the constraints");
  }
}

/// [initial] project = true keeps what the scene wrote: given values that no state satisfying
/// the constraints has are refused (bad input), naming the keys and the constraints violated.
void ModelBuilder::refuse_given_values(const InconsistentGivenValues& e) const {
  const std::string level = e.velocity_level ? "velocity" : "displacement";
  const auto& values = e.velocity_level ? spec_.initial.velocity : spec_.initial.displacement;
  std::string keys, rows;
  for (int d : e.given) {
    const auto& name = model_.dof_names[static_cast<std::size_t>(d)];
    for (const auto& [given, value] : values) {
      if (given == name) keys += (keys.empty() ? "" : ", ") + name + " = " + fmt(value);
    }
  }
  for (const auto& [row, residual] : e.violated) {
    rows += (rows.empty() ? "'" : ", '") + model_.constraints[static_cast<std::size_t>(row)].name +
            "' (residual " +
            computed_fmt(residual, "products of the initial coordinates, lengths and velocities") +
            ")";
  }
  rows += " at the closest state";
  fail({"initial." + level + "." + model_.dof_names[static_cast<std::size_t>(e.given.front())],
        spec_.initial.where.line},
       "project = true keeps the values given in [initial], but with " + level + " " + keys +
           " kept no initial state satisfies constraint" + (e.violated.size() == 1 ? " " : "s ") +
           rows +
           ": the given values are inconsistent with the constraints; change or "
           "remove one of them");
}

/// [initial] project = true: the least-change projection of (u0, v0) onto the constraints,
/// keeping the values given in [initial].
void ModelBuilder::project_initial() {
  const auto s = evaluator();
  const auto n = static_cast<std::size_t>(model_.dofs());
  std::vector<bool> given_u(n, false), given_v(n, false);
  for (const auto& [name, value] : spec_.initial.displacement)
    given_u[static_cast<std::size_t>(model_.dof_at(name))] = true;
  for (const auto& [name, value] : spec_.initial.velocity)
    given_v[static_cast<std::size_t>(model_.dof_at(name))] = true;
  std::vector<std::string> names;
  names.reserve(model_.constraints.size());
  for (const auto& c : model_.constraints) names.push_back(c.name);
  try {
    report_.initial_projection = project_initial_state(*s, 0.0, model_.u0, model_.v0, given_u,
                                                       given_v, model_.dof_names, names);
  } catch (const InconsistentGivenValues& e) {
    refuse_given_values(e);
  } catch (const std::runtime_error& e) {
    // A linear model's rows are dependent or not whatever the state: the rank check, which
    // otherwise comes later (models/assembly/build_model.cpp), names a dependent set and says
    // whether it conflicts; with redundant = "drop" the projection runs again without the dropped
    // rows. Without it a conflicting block was reported as a projection whose velocities no state
    // satisfies.
    if (!model_.is_nonlinear()) {
      check_finite();
      bool dropped = false;
      while (const auto dependent = check_rank()) {
        drop_constraint(*dependent);
        dropped = true;
      }
      if (dropped) {
        project_initial();
        return;
      }
    }
    fail(spec_.initial.where, e.what());
  }
  if (!model_.is_nonlinear()) {  // velocity rows integrate with the projected u(0)
    model_.constraints.clear();
    build_constraints();
  }
}

}  // namespace condyn
