// [initial] static = true: u(0) is the constrained static equilibrium of a linear model under the
// loads and prescribed values at t = 0 (models/assembly/static_equilibrium.hpp); v(0) stays as
// given.

#include <cmath>
#include <sstream>

#include "models/assembly/model_builder.hpp"
#include "models/assembly/static_equilibrium.hpp"

namespace condyn {

namespace {

// The equilibrium residual ‖K u + Aᵀλ − f‖∞ relative to the forces' size above which the solve
// is refused: a sound factorization leaves a few hundred ulps; more means a near-mechanism whose
// equilibrium double precision cannot resolve.
constexpr double kMaxStaticResidual = 1e-8;

}  // namespace

/// After the rank check (redundant rows dropped: they would make the saddle matrix singular) and
/// before the initial-consistency check, which then tests the equilibrium against every row.
/// A velocity row's position form integrates from a·u(0) of the state before this stage; the
/// equilibrium meets it (a·u = g(0)), so the rows stay valid as built.
void ModelBuilder::solve_static_initial() {
  const SourcePoint where{"initial.static", spec_.initial.where.line};
  if (model_.is_nonlinear()) {
    fail(where,
         "static = true needs a linear model (K u + Aᵀλ = f solved once); this model's forces or "
         "constraints depend on the state (nonlinear), and a static Newton iteration is not "
         "implemented: give the equilibrium in [initial] displacement instead");
  }
  model_.static_start = true;
  const Eigen::VectorXd f = model_.applied_forces(0.0);
  const Eigen::VectorXd g = model_.position_rhs(0, 0.0);
  StaticEquilibrium eq;
  try {
    eq = solve_static_equilibrium(*model_.K, model_.A, f, g);
  } catch (const NoStaticEquilibrium& e) {
    std::string dofs;
    for (int d : e.free_dofs)
      dofs += (dofs.empty() ? "" : ", ") + model_.dof_names[static_cast<std::size_t>(d)];
    fail(where, std::string("no static equilibrium: ") + e.what() +
                    (dofs.empty() ? "" : "; free to move: " + dofs) +
                    " (a mechanism: support it, constrain it or give it stiffness, or remove "
                    "static = true)");
  }
  if (!(eq.residual <= kMaxStaticResidual)) {
    fail(where, "the static equilibrium could not be solved accurately (relative residual " +
                    computed_fmt(eq.residual, "the loads, stiffness or displacements") +
                    "): the stiffness is nearly singular on the motions the "
                    "constraints allow");
  }
  model_.u0 = eq.u;
  std::ostringstream s;
  s.precision(3);
  s << "static equilibrium at t = 0 (sparse LU of [K Aᵀ; A 0], " << model_.dofs() << " DOFs, "
    << model_.constraint_count() << " constraints): max |u| = " << eq.u.lpNorm<Eigen::Infinity>()
    << ", relative residual " << eq.residual;
  // The ground motion is one of the loads at t = 0: a preload under gravity then a record that
  // does not start at rest includes it, which the line says rather than leave it to be found.
  if (spec_.ground_motion) {
    const double a0 = spec_.ground_motion->acceleration.value(0.0);
    if (a0 != 0.0) {
      s << "; the loads at t = 0 include the ground motion's -M r a_g(0), a_g(0) = " << a0
        << " (start the record at 0 for a preload without it)";
    }
  }
  report_.initial_projection = s.str();
}

}  // namespace condyn
