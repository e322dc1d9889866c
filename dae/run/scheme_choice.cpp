#include "dae/run/scheme_choice.hpp"

#include <algorithm>
#include <initializer_list>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "dae/formulations/eliminated_system.hpp"
#include "dae/formulations/multiplier_dae.hpp"
#include "dae/formulations/penalty_ode.hpp"
#include "dae/formulations/projected_ode.hpp"
#include "dae/integrators/stabilized_newmark_newton.hpp"
#include "models/core/massless_dofs.hpp"
#include "models/core/master_slave.hpp"

namespace condyn {

namespace {

/// Why a scheme cannot run a model, if it cannot (scheme_refusal() words it).
enum class Refusal {
  none,
  penalty_static_start,
  elimination_nonholonomic,
  penalty_dense_row,
  newmark_massless,
  rattle_model
};

/// The constraint row with the most entries, and their count (m = 0: row −1).
std::pair<int, long> longest_row(const Eigen::SparseMatrix<double>& A) {
  std::vector<long> entries(static_cast<std::size_t>(A.rows()), 0);
  for (int k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      ++entries[static_cast<std::size_t>(it.row())];
    }
  }
  const auto at = std::max_element(entries.begin(), entries.end());
  if (at == entries.end()) return {-1, 0};
  return {static_cast<int>(at - entries.begin()), *at};
}

/// Penalty's springs add w aᵢᵀaᵢ for each row aᵢ to K (and C): a row over L DOFs couples them
/// all, L² entries of the stiffness, as master-slave elimination's dense block would
/// (kMaxDenseGroupEntries): a row over 50,000 DOFs (a floor's average drift) is 2.5·10⁹.
bool penalty_too_dense(const Model& model) {
  const double entries = static_cast<double>(longest_row(model.A).second);
  return entries * entries > kMaxDenseGroupEntries;
}

/// The DOFs with no mass that no constraint row touches, at the start.
std::vector<int> unconstrained_massless(const Model& model) {
  const auto system = model.system->clone();
  const Eigen::SparseMatrix<double> M = system->mass(0.0, model.u0);
  return unconstrained_massless_dofs(M, system->constraint_jacobian(0.0, model.u0));
}

/// What RATTLE (dae/integrators/rattle_step.hpp) cannot integrate in `model`, or nothing: it is
/// the symplectic method of a conservative mechanism, M u'' = f(t, u) − Aᵀλ with M constant and
/// positive definite on the constraints' motions, and scleronomic position constraints.
std::optional<std::string> rattle_problem(const Model& model) {
  const auto system = model.system->clone();
  const Eigen::VectorXd& u = model.u0;
  const std::string why =
      "rattle integrates conservative mechanisms only (constant mass, forces "
      "independent of velocity, scleronomic position constraints): ";
  if (system->mass_jacobian(0.0, u, Eigen::VectorXd::Ones(model.dofs())).rows() > 0) {
    return why + "this model's mass matrix depends on its coordinates";
  }
  const std::vector<int> massless = unconstrained_massless(model);
  if (!massless.empty()) {
    return why + "DOF " + model.dof_names[static_cast<std::size_t>(massless.front())] +
           " has no mass and no constraint holds it (" + std::to_string(massless.size()) +
           " such DOFs)";
  }
  const Eigen::SparseMatrix<double>& C = system->damping(0.0, u, model.v0);
  // A nonlinear model's damping pattern is fixed (MechanicalSystem): stored entries mean forces
  // that depend on velocity somewhere, even where they vanish at the start.
  const bool damped =
      C.nonZeros() > 0 && (model.is_nonlinear() || C.coeffs().cwiseAbs().maxCoeff() > 0);
  if (damped) return why + "this model has damping (forces that depend on velocity)";
  for (int i = 0; i < model.constraint_count(); ++i) {
    const Constraint& c = model.constraints[static_cast<std::size_t>(i)];
    if (!system->position_rows()[static_cast<std::size_t>(i)]) {
      return why + "constraint '" + c.name + "' is written on velocities";
    }
    if (!c.position_value.is_constant()) {
      return why + "constraint '" + c.name + "' depends on time (rheonomic)";
    }
  }
  if (!model.drives.empty()) return why + "this mechanism has drives (rheonomic constraints)";
  return std::nullopt;
}

Refusal refusal_of(const Model& model, Scheme scheme) {
  if (scheme == Scheme::penalty && model.static_start && model.constraint_count() > 0) {
    return Refusal::penalty_static_start;
  }
  if (scheme == Scheme::rattle && rattle_problem(model)) return Refusal::rattle_model;
  // The Newmark family starts (and restarts at load steps) from ü solved at acceleration level,
  // which a DOF without mass outside the constraints leaves undetermined.
  if (fixed_step(scheme) && !unconstrained_massless(model).empty()) {
    return Refusal::newmark_massless;
  }
  if (!model.is_nonlinear()) {
    return scheme == Scheme::penalty && penalty_too_dense(model) ? Refusal::penalty_dense_row
                                                                 : Refusal::none;
  }
  if (scheme == Scheme::elimination) {
    // Coordinate partitioning (dae/formulations/partitioned_ode.hpp) solves every row with a
    // position form; a nonholonomic row has none.
    const bool nonholonomic = std::any_of(model.constraints.begin(), model.constraints.end(),
                                          [](const Constraint& c) { return c.nonholonomic; });
    return nonholonomic ? Refusal::elimination_nonholonomic : Refusal::none;
  }
  return Refusal::none;
}

/// "a, b or c": the candidates this model is not refused under, so that a refusal never points
/// to a scheme that refuses the same scene (projection's once named penalty on a static start).
std::string usable(const Model& model, std::initializer_list<Scheme> candidates) {
  std::vector<std::string> names;
  for (Scheme s : candidates) {
    if (refusal_of(model, s) == Refusal::none) names.emplace_back(to_string(s));
  }
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  }
  return out;
}

}  // namespace

std::optional<std::string> scheme_refusal(const Model& model, Scheme scheme) {
  using S = Scheme;
  const auto dae_schemes = {S::index1, S::baumgarte, S::ggl, S::index2, S::index3, S::projection};
  switch (refusal_of(model, scheme)) {
    case Refusal::none:
      return std::nullopt;
    case Refusal::penalty_static_start:
      return "[initial] static = true gives the equilibrium under exact constraints, where "
             "penalty's springs carry no force: under penalty the structure would not start at "
             "rest (its supports unloaded). Use another scheme, or give the displacements";
    case Refusal::elimination_nonholonomic:
      return "elimination cannot treat a nonholonomic constraint: master-slave elimination "
             "and its nonlinear form, coordinate partitioning, solve the constraints for slave "
             "(dependent) displacements, and a nonintegrable velocity constraint has no "
             "displacement form to solve. The chapter says so: nonholonomic "
             "MFCs \"are non treatable by master-slave methods unless they integrate to "
             "holonomic constraints\" (§5.6), and for them \"only the Lagrange multiplier "
             "method, used with extreme care, offers hope\" (§5.3.1). Use " +
             usable(model, dae_schemes);
    case Refusal::penalty_dense_row: {
      const auto [row, entries] = longest_row(model.A);
      std::ostringstream s;
      s << "penalty: constraint '" << model.constraints[static_cast<std::size_t>(row)].name
        << "' has " << entries << " terms; its spring couples them all, a dense block of "
        << static_cast<double>(entries) * static_cast<double>(entries)
        << " entries in the stiffness and damping (beyond " << kMaxDenseGroupEntries << "); use "
        << usable(model, {S::index1, S::ggl, S::automatic}) << ", which keep it as one multiplier";
      return s.str();
    }
    case Refusal::rattle_model:
      return *rattle_problem(model) + ". Use " +
             usable(model, {S::ggl, S::newmark, S::generalized_alpha});
    case Refusal::newmark_massless: {
      const std::vector<int> dofs = unconstrained_massless(model);
      return std::string(to_string(scheme)) + " does not treat massless DOFs outside the " +
             "constraints yet (" + std::to_string(dofs.size()) + ", the first " +
             model.dof_names[static_cast<std::size_t>(dofs.front())] +
             "): its start needs the accelerations of every DOF. Use " +
             usable(model, {S::automatic, S::ggl, S::index1});
    }
  }
  return std::nullopt;
}

bool uses_mixed_treatment(const Model& model, Scheme resolved, const SolveSpec& settings) {
  if (resolved == Scheme::automatic || !mixes(resolved) || model.constraint_count() == 0)
    return false;
  return settings.treatment == SolveSpec::Treatment::mixed ||
         (settings.treatment == SolveSpec::Treatment::automatic &&
          settings.scheme == Scheme::automatic);
}

const char* treatment_name(const Model& model, Scheme resolved, const SolveSpec& settings) {
  if (resolved == Scheme::automatic || !mixes(resolved) || model.constraint_count() == 0)
    return nullptr;
  return uses_mixed_treatment(model, resolved, settings) ? "mixed" : "multipliers";
}

namespace {

/// auto on a linear model with every row kept as a multiplier ([solve] constraints =
/// "multipliers"): elimination or GGL, whichever factors the smaller Newton matrix.
SchemeChoice cheaper_of_elimination_and_ggl(SchemeDecisions& decisions, const SolveSpec& settings) {
  SolveSpec as_ggl = settings, as_elimination = settings;
  as_ggl.scheme = Scheme::ggl;
  as_elimination.scheme = Scheme::elimination;
  const SystemSize ggl = decisions.size(as_ggl);
  SystemSize elimination;
  try {
    elimination = decisions.size(as_elimination);
  } catch (const std::invalid_argument& why) {
    return {Scheme::ggl, std::string("elimination cannot treat this model (") + why.what() +
                             "): GGL, which holds the constraints to the Newton tolerance"};
  }
  std::ostringstream figures;
  figures << "elimination " << elimination.unknowns << " unknowns, "
          << elimination.jacobian_nonzeros << " Jacobian nonzeros; GGL " << ggl.unknowns << ", "
          << ggl.jacobian_nonzeros;
  if (elimination.jacobian_nonzeros <= ggl.jacobian_nonzeros) {
    return {Scheme::elimination,
            "every constraint is linear and integrable, and elimination "
            "solves the smaller system (" +
                figures.str() + ")"};
  }
  return {Scheme::ggl, "the master-slave transform fills in: GGL solves the smaller system (" +
                           figures.str() + ")"};
}

/// The size of a fixed-step scheme's system (the Newmark family, RATTLE): the state [u; v; λ]; the
/// Newton matrix [M + C + K (+ curvature) Aᵀ; A 0] (its linear part's pattern at the start:
/// dae/integrators/newmark_newton.hpp), RATTLE's [M Aᵀ; A 0] (dae/integrators/rattle_step.hpp);
/// over `system`, the reduced one (`eliminated`, else null) under the mixed treatment. `size`
/// carries what is already known (dense, reduced).
SystemSize fixed_step_size(const Model& model, const MechanicalSystem& system,
                           const EliminatedSystem* eliminated, Scheme scheme,
                           const SolveSpec& settings, SystemSize size) {
  const auto evaluated = system.clone();
  const Eigen::VectorXd u = eliminated ? eliminated->restrict(model.u0) : model.u0;
  const Eigen::VectorXd v = eliminated ? eliminated->restrict(model.v0) : model.v0;
  Eigen::SparseMatrix<double> S = evaluated->mass(0.0, u);
  for (const auto* B : {&evaluated->stiffness(0.0, u, v), &evaluated->damping(0.0, u, v)}) {
    if (newmark_family(scheme) && B->rows() == S.rows() && B->cols() == S.cols()) S += *B;
  }
  size.unknowns = 2 * evaluated->dofs() + evaluated->constraints();
  size.jacobian_nonzeros = S.nonZeros() + 2 * evaluated->constraint_jacobian(0.0, u).nonZeros();
  if (newmark_family(scheme) &&
      settings.newmark_family.constraints == NewmarkConstraints::stabilized) {
    // [u; v; λ; μ] and the stabilized matrix (dae/integrators/stabilized_newmark_newton.hpp).
    const StabilizedSize stabilized = stabilized_size(*evaluated, !model.is_nonlinear(), 0.0, u, v);
    size.unknowns += stabilized.mu;
    if (stabilized.mu > 0) size.jacobian_nonzeros = stabilized.nonzeros;
  }
  return size;
}

}  // namespace

SchemeChoice choose_scheme(const Model& model, const SolveSpec& settings) {
  SchemeDecisions decisions(model);
  return decisions.choose(settings);
}

SchemeChoice SchemeDecisions::choose(const SolveSpec& settings) {
  const Model& model = model_;
  if (settings.scheme != Scheme::automatic) return {settings.scheme, "requested"};
  const bool pure = settings.treatment == SolveSpec::Treatment::multipliers;
  if (model.is_nonlinear()) {
    std::string why =
        "nonlinear model: GGL (stabilized index 2) holds position and velocity constraints to "
        "the Newton tolerance at every step, and treats nonholonomic rows too; elimination "
        "(coordinate partitioning, by name) solves the constraints by Newton at every "
        "evaluation of a dense-Jacobian ODE, a check path rather than the cheaper one";
    // Said only where it happens: a sleigh or Andrews' mechanism has no such row.
    if (!pure && !treatment()->eliminated.empty()) {
      why += "; its constant linear rows eliminated where that stays sparse";
    }
    return {Scheme::ggl, why};
  }
  if (model.constraint_count() == 0) {
    return {Scheme::elimination, "no constraints: the model is integrated as it is"};
  }
  if (pure) return cheaper_of_elimination_and_ggl(*this, settings);
  // Every row of a linear model is linear with constant coefficients, hence holonomic or
  // integrable: each group is eliminated unless its master-slave transform fills in.
  const ConstraintTreatment* treated = nullptr;
  try {
    treated = treatment().get();
  } catch (const std::invalid_argument& why) {
    return {Scheme::ggl, std::string("master-slave elimination cannot treat this model (") +
                             why.what() + "): GGL with a multiplier for every row"};
  }
  if (treated->kept.empty()) {
    return {Scheme::elimination,
            "every constraint is linear and integrable, and its elimination stays sparse"};
  }
  return {Scheme::ggl, "GGL with mixed treatment: " + std::to_string(treated->eliminated.size()) +
                           " rows eliminated, " + std::to_string(treated->kept.size()) +
                           " kept as multipliers (their master-slave transform would fill in, "
                           "or their coupled group is too large to build it)"};
}

void refuse_inapplicable(const Model& model, Scheme scheme, const SourcePoint& chosen_at) {
  if (auto why = scheme_refusal(model, scheme)) throw SchemeNotApplicable(*why, chosen_at);
}

SystemSize system_size(const Model& model, const SolveSpec& settings) {
  try {
    return SchemeDecisions(model).size(settings);
  } catch (const SchemeNotApplicable& why) {
    throw SchemeNotApplicable(why.what(), settings.scheme_where);
  }
}

const std::shared_ptr<const ConstraintTreatment>& SchemeDecisions::treatment() {
  if (!treatment_)
    treatment_ = std::make_shared<const ConstraintTreatment>(treat_constraints(model_));
  return treatment_;
}

const std::shared_ptr<const ReducedSystem>& SchemeDecisions::reduced(
    const std::vector<std::string>& slaves) {
  if (!reduced_) reduced_ = std::make_shared<const ReducedSystem>(reduce(model_, slaves));
  return reduced_;
}

const std::shared_ptr<const ReducedOde>& SchemeDecisions::reduced_ode(
    const std::vector<std::string>& slaves) {
  if (!reduced_ode_) {
    // The ODE keeps a reference to the reduction: whoever keeps it keeps reduced() too.
    reduced_ode_ = std::make_shared<const ReducedOde>(model_, *reduced(slaves));
  }
  return reduced_ode_;
}

SystemSize SchemeDecisions::size(const SolveSpec& settings) {
  return size_as(settings.scheme == Scheme::automatic ? choose(settings).scheme : settings.scheme,
                 settings);
}

SystemSize SchemeDecisions::size_as(Scheme scheme, const SolveSpec& settings) {
  const Model& model = model_;
  refuse_inapplicable(model, scheme, settings.scheme_where);
  // The matrix IDA's Newton iterations factor: the condensed one when asked for.
  const bool condensed =
      (settings.condensed_newton || settings.linear_solver == SolveSpec::LinearSolver::cholmod) &&
      !settings.dense_linear_solver;
  SystemSize size;
  size.dense = settings.dense_linear_solver;
  if (scheme == Scheme::elimination && model.is_nonlinear()) {
    // Coordinate partitioning: the independent coordinates and their velocities, n − m each for
    // independent rows, under CVODE's dense difference-quotient Jacobian.
    size.unknowns = 2 * (model.dofs() - model.constraint_count());
    size.dense = true;
    size.jacobian_nonzeros = static_cast<long>(size.unknowns) * size.unknowns;
    return size;
  }
  if (scheme == Scheme::elimination) {
    const ReducedOde& ode = *reduced_ode(settings.slaves);
    size.unknowns = ode.size();
    size.condensed = condensed;
    size.reduced = true;
    size.jacobian_nonzeros =
        condensed ? ode.newton_system()->nonzeros() : ode.jacobian_pattern().nonZeros();
    return size;
  }
  const MechanicalSystem* system = model.system.get();
  if (uses_mixed_treatment(model, scheme, settings)) {
    if (!mixed_) {
      const ConstraintTreatment& treated = *treatment();
      mixed_ = treated.eliminated.empty()
                   ? nullptr
                   : std::make_shared<const EliminatedSystem>(model, treated);
    }
    if (*mixed_) system = mixed_->get();
    size.reduced = *mixed_ != nullptr;
  }
  if (fixed_step(scheme)) {
    const auto* eliminated =
        size.reduced ? dynamic_cast<const EliminatedSystem*>(mixed_->get()) : nullptr;
    return fixed_step_size(model, *system, eliminated, scheme, settings, size);
  }
  if (scheme == Scheme::penalty && model.is_nonlinear()) {
    // The augmented Lagrangian (dae/formulations/augmented_lagrangian_ode.hpp): [u; v] under
    // Adams' functional iteration, no Newton matrix; what it factors is M + AᵀαA.
    const auto evaluated = model.system->clone();
    const Eigen::SparseMatrix<double> A = evaluated->constraint_jacobian(0.0, model.u0);
    const Eigen::SparseMatrix<double> S =
        evaluated->mass(0.0, model.u0) + Eigen::SparseMatrix<double>(A.transpose() * A);
    size.unknowns = 2 * model.dofs();
    size.jacobian_nonzeros = S.nonZeros();
    return size;
  }
  if (scheme == Scheme::penalty) {
    const PenaltyOde ode(*model.system, penalty_weights(model, settings));
    size.unknowns = ode.size();
    size.condensed = condensed;
    size.jacobian_nonzeros =
        condensed ? ode.newton_system()->nonzeros() : ode.jacobian_pattern().nonZeros();
    return size;
  }
  if (scheme == Scheme::projection) {
    const ProjectedOde ode(*system, model.u0, !model.nonlinear, &model);
    // The matrix the Newton iterations factor: the sparse saddle point (linear or nonlinear
    // model), else CVODE's dense one.
    size.unknowns = ode.size();
    const auto newton = ode.newton_system();
    size.condensed = newton != nullptr;
    size.dense = !size.condensed;
    size.jacobian_nonzeros =
        newton ? newton->nonzeros() : static_cast<long>(ode.size()) * ode.size();
    return size;
  }
  // The Jacobian's pattern does not depend on the values of Baumgarte's gains, only on their
  // being nonzero: unit gains size it without the model's frequencies (a Lanczos run at scale).
  const double gain = scheme == Scheme::baumgarte ? 1.0 : 0.0;
  const MultiplierDae dae(*system, scheme, gain, gain, !model.nonlinear);
  size.unknowns = dae.size();
  const auto newton = condensed ? dae.newton_system() : nullptr;
  size.condensed = newton != nullptr;
  size.jacobian_nonzeros = newton ? newton->nonzeros() : dae.jacobian_pattern().nonZeros();
  return size;
}

}  // namespace condyn
