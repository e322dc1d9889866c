// Input checks of build_model(): time functions that stay finite over the horizon
// (magnitude_bound), finite matrices and initial state, magnitude warnings, the memory
// estimate, and DOFs that nothing defines.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "models/assembly/model_builder.hpp"
#include "models/core/memory_estimate.hpp"
#include "models/core/number_cell.hpp"

namespace condyn {

namespace {

// exp(709) is the largest finite double; leave headroom for amplitudes and derivatives.
constexpr double kMaxExponent = 700.0;

}  // namespace

// The shortest text that reads back as v: a figure in a message is the value itself, so a step
// at 2.0000000000000004 is never shown as "2" beside a t_end of 2.
std::string fmt(double v) { return shortest_number(v); }

std::string computed_fmt(double v, const std::string& cause) {
  if (std::isfinite(v)) return fmt(v);
  return std::string(std::isnan(v) ? "not a number" : "infinite") + " (" + cause +
         " overflow the double range)";
}

/// An upper bound of |d^order/dt^order term(t)| over [0, t_end], order in {0, 1, 2}; infinite when
/// the term leaves the double range there.
double magnitude_bound(const TimeTerm& term, int order, double t_end) {
  if (term.is_zero()) return 0.0;
  switch (term.kind) {
    case TimeTerm::Kind::step:
      return order == 0 ? std::abs(term.amplitude) : 0.0;
    case TimeTerm::Kind::polynomial: {
      double sum = 0.0;
      for (std::size_t k = static_cast<std::size_t>(order); k < term.coefficients.size(); ++k) {
        if (term.coefficients[k] == 0.0) continue;
        double factor = std::abs(term.coefficients[k]);
        for (int j = 0; j < order; ++j)
          factor *= static_cast<double>(k - static_cast<std::size_t>(j));
        sum += factor * std::pow(t_end, static_cast<double>(k - static_cast<std::size_t>(order)));
      }
      return sum;
    }
    case TimeTerm::Kind::harmonic:
      // Integrated (an antiderivative): |∫₀ᵗ A sin| <= |A| t, its derivatives the integrand's.
      if (term.integrated) {
        return order == 0 ? std::abs(term.amplitude) * t_end
                          : std::abs(term.amplitude) * std::pow(std::abs(term.omega), order - 1);
      }
      return std::abs(term.amplitude) * std::pow(std::abs(term.omega), order);
    case TimeTerm::Kind::exponential: {
      const double grown = std::abs(term.amplitude) * std::exp(std::max(term.rate * t_end, 0.0));
      if (term.integrated) {
        return order == 0 ? grown * t_end : grown * std::pow(std::abs(term.rate), order - 1);
      }
      return grown * std::pow(std::abs(term.rate), order);
    }
    case TimeTerm::Kind::table:
      if (order == 2) return 0.0;
      return std::abs(term.amplitude) *
             (order == 0 ? term.table->max_abs_value : term.table->max_abs_slope);
    case TimeTerm::Kind::record:
      return std::abs(term.amplitude) * term.record->bound[static_cast<std::size_t>(order)];
  }
  return 0.0;
}

/// The largest of the bounds of f, f' and f'' over [0, t_end] (infinite on overflow).
double magnitude_bound(const TimeFunction& f, double t_end) {
  double worst = 0.0;
  for (int order = 0; order <= 2; ++order) {
    double sum = 0.0;
    for (const auto& term : f.terms()) sum += magnitude_bound(term, order, t_end);
    worst = std::max(worst, sum);
  }
  return worst;
}

bool all_finite(const Eigen::SparseMatrix<double>& m) {
  for (Eigen::Index k = 0; k < m.nonZeros(); ++k) {
    if (!std::isfinite(m.valuePtr()[k])) return false;
  }
  return true;
}

/// f, f' and f'' must stay finite over [0, t_end]: an overflowing load or right-hand side would
/// reach the solver as inf or NaN.
TimeFunction ModelBuilder::acting_in_run(const TimeFunction& f, const SourcePoint& where) {
  std::vector<double> late;
  TimeFunction acting = f.acting_until(spec_.solve.t_end, late);
  for (double t : late) {
    report_.warnings.push_back(where.path + ": the step at t = " + fmt(t) +
                               " starts after t_end = " + fmt(spec_.solve.t_end) +
                               " and has no effect on this run");
  }
  for (const auto& term : acting.terms()) {
    if (term.kind != TimeTerm::Kind::table || !term.table || term.table->times.empty()) continue;
    // A record that starts late on a nonzero value acts from t = 0 at that value (a time-shifted
    // accelerogram would be a step of ground acceleration at 0): said as its cut end is.
    const double start = term.table->times.front();
    const double first = term.amplitude * term.table->values.front();
    if (start > 0.0 && first != 0.0) {
      report_.warnings.push_back(
          where.path + ": " + term.table->file + " starts at t = " + fmt(start) +
          (start >= spec_.solve.t_end ? ", after t_end = " + fmt(spec_.solve.t_end) + "," : "") +
          " on a nonzero value: " + fmt(first) +
          " acts from t = 0 (a table is constant before its first sample); add a sample at t = 0 "
          "to say what precedes");
    }
    const double end = term.table->times.back();
    const double last = term.amplitude * term.table->values.back();
    if (end < spec_.solve.t_end && last != 0.0) {
      report_.warnings.push_back(
          where.path + ": " + term.table->file + " ends at t = " + fmt(end) +
          ", before t_end = " + fmt(spec_.solve.t_end) + ", on a nonzero value: " + fmt(last) +
          " is held from there on (a table is constant after its last sample); add a sample "
          "to say what follows");
    }
  }
  return acting;
}

void ModelBuilder::check_time_function(const TimeFunction& f, const SourcePoint& where,
                                       bool prescribed_displacement) const {
  if (f.has_record() && !prescribed_displacement) {
    fail(where,
         "a displacement record prescribes a displacement, not a force or a ground "
         "acceleration: give it as the value of a [[constraint]] on the supported DOF "
         "(terms = { u1 = 1.0 }), or a recorded ground acceleration as a table in "
         "[ground_motion]");
  }
  for (const auto& term : f.terms()) {
    if (term.kind == TimeTerm::Kind::exponential &&
        std::abs(term.rate) * spec_.solve.t_end > kMaxExponent && term.rate > 0) {
      fail(where,
           "exp(" + fmt(term.rate) + "*t) overflows before t_end = " + fmt(spec_.solve.t_end));
    }
  }
  if (!std::isfinite(magnitude_bound(f, spec_.solve.t_end))) {
    fail(where, f.describe() +
                    " or its first two time derivatives overflow the double range "
                    "(about 1.8e308) before t_end = " +
                    fmt(spec_.solve.t_end));
  }
}

/// The last line of defence against a silent inf or NaN: whatever the checks above let through,
/// the matrices and the initial state handed to the solvers are finite.
void ModelBuilder::check_finite() const {
  const std::pair<const Eigen::SparseMatrix<double>*, const char*> matrices[] = {
      {&model_.M, "mass matrix M"},
      {&model_.C, "damping matrix C"},
      {&*model_.K, "stiffness matrix K"},
      {&model_.A, "constraint matrix A"}};
  // A nonlinear model's matrices are its linearization at (u0, v0): too large an initial state
  // is the likelier cause there.
  const bool at_start = model_.is_nonlinear() && spec_.initial.given();
  for (const auto& [mat, name] : matrices) {
    if (!all_finite(*mat)) {
      fail(at_start ? spec_.initial.where : spec_.model.where,
           std::string("the ") + name +
               (at_start ? " linearized at the initial state has entries beyond the double "
                           "range: are the initial values too large?"
                         : " has entries beyond the double range: the scene's numbers are too "
                           "large"));
    }
  }
  // Finite matrices whose ratios are not: K_ii / M_ii (a natural frequency squared, about) of
  // 3e160 / 1e-160 made the frequency estimates fail inside the eigensolver, exit 1 and no key.
  {
    const Eigen::VectorXd m = model_.M.diagonal(), k = model_.K->diagonal();
    for (Eigen::Index i = 0; i < m.size(); ++i) {
      if (m[i] > 0.0 && !std::isfinite(k[i] / m[i])) {
        const ModelSpec& ms = spec_.model;
        const SourcePoint& where = ms.stiffness_file.given()          ? ms.stiffness_file.where
                                   : !ms.stiffness_where.path.empty() ? ms.stiffness_where
                                                                      : ms.where;
        fail(where, "DOF '" + model_.dof_names[static_cast<std::size_t>(i)] +
                        "': K_ii / M_ii = " + fmt(k[i]) + " / " + fmt(m[i]) +
                        " overflows the double range (its natural frequency squared is not "
                        "representable): check the units");
      }
    }
  }
  if (!model_.u0.allFinite() || !model_.v0.allFinite()) {
    fail(spec_.initial.given() ? spec_.initial.where : spec_.model.where,
         "the initial state is not finite (it overflows the double range)");
  }
  // Finite values whose forces are not (K u(0) with u(0) = 1e308): the run would fail at t = 0
  // with "the solution became non-finite", a message about the integration, not the input.
  if (!model_.is_nonlinear() && spec_.initial.given()) {
    const Eigen::VectorXd ku = *model_.K * model_.u0;
    const Eigen::VectorXd cv = model_.has_damping() ? Eigen::VectorXd(model_.C * model_.v0)
                                                    : Eigen::VectorXd::Zero(model_.dofs());
    const Eigen::VectorXd mv = model_.M * model_.v0;
    if (!ku.allFinite() || !cv.allFinite() || !mv.allFinite()) {
      std::string what = "displacements times the model's stiffness";
      if (ku.allFinite()) {
        what = std::string("velocities times the model's ") + (cv.allFinite() ? "mass" : "damping");
      }
      fail(spec_.initial.where,
           "the initial " + what + " overflow the double range (about 1.8e308): check the units");
    }
  }
}

/// Warns (does not refuse) about magnitudes that double precision cannot carry well: M, C, K or
/// A whose largest entry lies beyond 1e±15 (a unit mistake, most likely), and diagonals of M or
/// K whose largest and smallest positive entries differ by more than 1/eps ≈ 4.5e15 (the soft
/// or light DOFs are then lost in the roundoff of the stiff or heavy ones); initial values beyond
/// 1e15 likewise.
void ModelBuilder::check_magnitudes() {
  constexpr double kFar = 1e15, kSpread = 4.5e15;
  const std::pair<const Eigen::SparseMatrix<double>*, const char*> matrices[] = {
      {&model_.M, "mass matrix M"},
      {&model_.C, "damping matrix C"},
      {&*model_.K, "stiffness matrix K"},
      {&model_.A, "constraint matrix A"}};
  for (const auto& [mat, name] : matrices) {
    double hi = 0.0;
    double dlo = std::numeric_limits<double>::infinity(), dhi = 0.0;
    for (int k = 0; k < mat->outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, k); it; ++it) {
        const double a = std::abs(it.value());
        if (a == 0.0) continue;
        hi = std::max(hi, a);
        if (it.row() == it.col() && it.value() > 0.0) {
          dlo = std::min(dlo, it.value());
          dhi = std::max(dhi, it.value());
        }
      }
    }
    // The largest entry sets the matrix's scale; single tiny entries are roundoff (cos 90°).
    if (hi > kFar || (hi > 0.0 && hi < 1.0 / kFar)) {
      report_.warnings.push_back(std::string("the ") + name + " has entries up to magnitude " +
                                 fmt(hi) + ": beyond 1e-15 ... 1e15, check the units");
    }
    const bool diagonal_matters = mat == &model_.M || mat == &*model_.K;
    if (diagonal_matters && dhi > 0.0 && dhi / dlo > kSpread) {
      report_.warnings.push_back(std::string("the diagonal of the ") + name + " spans " + fmt(dlo) +
                                 " to " + fmt(dhi) + " (ratio " + fmt(dhi / dlo) +
                                 "): beyond 1/eps of double precision (4.5e15), the smallest "
                                 "entries are lost in roundoff");
    }
  }
  // Initial values beyond 1e15: the motion about them is below their roundoff unless it is as
  // large (a body moved by 1e30 and loaded to move by 0.01 stays at exactly 1e30).
  for (const auto& [values, name] :
       {std::pair{&model_.u0, "displacements"}, std::pair{&model_.v0, "velocities"}}) {
    const double hi = values->size() > 0 ? values->cwiseAbs().maxCoeff() : 0.0;
    if (hi > kFar) {
      report_.warnings.push_back(std::string("[initial] ") + name + " up to magnitude " + fmt(hi) +
                                 ": beyond 1e15, motion smaller than 1e-16 of them is lost in "
                                 "roundoff; check the units");
    }
  }
}

/// No fixed limit on DOFs or constraints: a model is refused here only when even the least any
/// scheme holds (models/core/memory_estimate.hpp) exceeds what the machine has available. The
/// estimate of the scheme a run integrates is stated by `info` and checked by `run`
/// (dae/run/scheme_memory.hpp).
void ModelBuilder::check_size() {
  const ModelSizes sizes = model_sizes(model_);
  const std::optional<double> available = available_memory_bytes();
  if (!available) return;
  if (const auto refusal =
          memory_refusal(sizes, least_memory_estimate(sizes), "any scheme", *available)) {
    fail(spec_.model.where, *refusal);
  }
}

void ModelBuilder::check_degenerate_dofs() const {
  const int n = model_.dofs();
  std::vector<bool> has(static_cast<std::size_t>(n), false);
  for (const auto* mat : {&model_.M, &*model_.K, &model_.C, &model_.A}) {
    for (int k = 0; k < mat->outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, k); it; ++it) {
        if (it.value() != 0.0) has[static_cast<std::size_t>(it.col())] = true;
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!has[static_cast<std::size_t>(i)])
      fail_undefined_motion(model_.dof_names[static_cast<std::size_t>(i)]);
  }
}

void ModelBuilder::fail_undefined_motion(const std::string& name) const {
  // A nonlinear model's A is its constraints' gradient at u(0), which can vanish on a DOF they do
  // involve (straight rigid members, across their line).
  fail(spec_.model.where,
       "DOF '" + name + "' has neither mass nor stiffness nor damping nor a constraint" +
           (model_.is_nonlinear()
                ? std::string(" acting on it at the initial state (a nonlinear constraint "
                              "through it, such as straight rigid members, can have a zero "
                              "gradient there: give it mass, or start it off that line)")
                : std::string()) +
           ": its motion is undefined");
}

void ModelBuilder::check_tolerance() {
  if (spec_.solve.rtol > 1e-2) {
    report_.warnings.push_back("rtol " + fmt(spec_.solve.rtol) +
                               " asks for fewer than 2 correct digits");
  }
}

}  // namespace condyn
