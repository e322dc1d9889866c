#include <memory>
#include <sstream>
#include <utility>

#include "dae/formulations/multiplier_recovery.hpp"
#include "dae/formulations/partitioned_ode.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/cvode_integrator.hpp"
#include "dae/integrators/ida_integrator.hpp"

namespace condyn {

void run_elimination(const Model& model, const ReducedSystem& reduced, ReducedOde& ode,
                     const ObservedRun& run) {
  const auto& masters = reduced.transform.masters;
  const int nm = static_cast<int>(masters.size());
  Eigen::VectorXd y0(2 * nm);
  for (int k = 0; k < nm; ++k) {
    y0[k] = model.u0[masters[static_cast<std::size_t>(k)]];
    y0[nm + k] = model.v0[masters[static_cast<std::size_t>(k)]];
  }
  const auto& T = reduced.transform.T;
  const auto& G = reduced.transform.G;
  const MultiplierRecovery recover(model);
  Observation observe;
  observe.full_state = [&](double t, const Eigen::VectorXd& y) {
    Eigen::VectorXd u = T * y.head(nm), v = T * y.tail(nm);
    if (reduced.rheonomic) {
      u += G * model.position_rhs(0, t);
      v += G * model.position_rhs(1, t);
    }
    return std::make_pair(u, v);
  };
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    Eigen::VectorXd a = T * ode.acceleration(t, y.head(nm), y.tail(nm));
    if (reduced.rheonomic) a += G * model.position_rhs(2, t);
    return recover(t, u, v, a);
  };
  observe.drift_at_every_step = false;
  run([&](const IntegratorOptions& o, SolveSummary& s) { return integrate(ode, y0, o, s); },
      observe);
}

namespace {

/// The Newton tolerance of the dependent coordinates: this fraction of the displacements' atol,
/// so that what the iteration leaves (quadratically less than its last correction) is far below
/// what the error test accepts of the independent ones, and the right-hand side is smooth to
/// CVODE's difference quotients.
constexpr double kNewtonMargin = 1e-3;

/// The summary's note: the partition, the Newton iteration and every re-partition.
std::string partition_note(const Model& model, const PartitionedOde& ode,
                           const std::vector<int>& first_independent) {
  const auto& names = model.dof_names;
  std::ostringstream s;
  s << "coordinate partitioning: " << first_independent.size() << " independent of " << model.dofs()
    << " coordinates at the start (" << dof_list(names, first_independent)
    << "), the rest solved by Newton to " << ode.newton_tolerance() << " ("
    << ode.newton_iterations() << " iterations)";
  if (ode.matrix_free()) {
    s << "; CVODE's Newton systems by GMRES on difference-quotient products (" << ode.size()
      << " unknowns, above the dense Jacobian's " << PartitionedOde::kDenseJacobianLimit << ")";
  }
  const auto& log = ode.repartitions();
  if (log.empty()) return s.str() + ", no re-partition";
  s << "; " << log.size() << (log.size() == 1 ? " re-partition" : " re-partitions");
  constexpr std::size_t kListed = 6;
  for (std::size_t k = 0; k < log.size() && k < kListed; ++k) {
    s << (k == 0 ? ": " : ", ") << "t = " << log[k].t << " ("
      << dof_list(names, log[k].now_independent) << " independent, "
      << dof_list(names, log[k].now_dependent) << " dependent; quality " << log[k].quality << ")";
  }
  if (log.size() > kListed) s << " and " << log.size() - kListed << " more";
  return s.str();
}

/// The options of a partitioned run: every state the loop hands out (outputs, steps, quadrature
/// points) is mapped to the full one at once, with the partition it was computed in, into
/// y = [u; u'] and y' = [u'; u''; λ]: a re-partition changes what the ODE's state means. Rows
/// go to the caller's sink or into `kept`.
IntegratorOptions full_state_options(const IntegratorOptions& o, const PartitionedOde& ode,
                                     RawTrajectory& kept) {
  const auto expand = [&ode](double t, const Eigen::VectorXd& y) {
    PartitionedOde::Full f = ode.full(t, y);
    Eigen::VectorXd full_y(2 * f.u.size()), full_yp(2 * f.u.size() + f.lambda.size());
    full_y << f.u, f.v;
    full_yp << f.v, f.a, f.lambda;
    return std::make_pair(full_y, full_yp);
  };
  IntegratorOptions out = o;
  out.on_output = [&kept, sink = o.on_output, expand](double t, const Eigen::VectorXd& y,
                                                      const Eigen::VectorXd&,
                                                      const Eigen::VectorXd& integrals) {
    auto [fy, fyp] = expand(t, y);
    if (sink) {
      sink(t, fy, fyp, integrals);
      return;
    }
    kept.y.push_back(std::move(fy));
    kept.yp.push_back(std::move(fyp));
    if (integrals.size() > 0) kept.integrals.push_back(integrals);
  };
  if (o.on_step) {
    out.on_step = [step = o.on_step, expand](double t, const Eigen::VectorXd& y) {
      step(t, expand(t, y).first);
    };
  }
  if (o.integrand) {
    out.integrand = [f = o.integrand, expand](double t, const Eigen::VectorXd& y,
                                              const Eigen::VectorXd&) {
      auto [fy, fyp] = expand(t, y);
      return f(t, fy, fyp);
    };
  }
  if (o.integrand_jump) {
    out.integrand_jump = [f = o.integrand_jump, expand](double t, const Eigen::VectorXd& before,
                                                        const Eigen::VectorXd& after) {
      return f(t, expand(t, before).first, expand(t, after).first);
    };
  }
  return out;
}

}  // namespace

void run_partitioned_elimination(const Model& model, const ObservedRun& run) {
  const int n = model.dofs();
  std::unique_ptr<PartitionedOde> ode;
  std::vector<int> first_independent;
  Observation observe;
  observe.full_state = full_state_prefix(n);
  // λ of the full equations at the state (the KKT solve of the accelerations), carried in y'.
  observe.multipliers = [n](double, const Eigen::VectorXd&, const Eigen::VectorXd& yp,
                            const Eigen::VectorXd&, const Eigen::VectorXd&) {
    return Eigen::VectorXd(yp.tail(yp.size() - 2 * static_cast<Eigen::Index>(n)));
  };
  observe.drift_at_every_step = false;
  observe.on_finish = [&](SolveSummary& summary) {
    if (ode)
      summary.add_note(RunNote::Kind::treatment, partition_note(model, *ode, first_independent));
  };
  run(
      [&](const IntegratorOptions& o, SolveSummary& s) {
        ode = std::make_unique<PartitionedOde>(model, o.output_times.front());
        ode->set_newton_tolerance(kNewtonMargin * o.atol);
        first_independent = ode->partition().independent;
        RawTrajectory kept;
        try {
          RawTrajectory raw =
              integrate_ode(*ode, ode->initial_state(), full_state_options(o, *ode, kept), s);
          kept.t = std::move(raw.t);  // the loop's own times (those of the sink's rows too)
          return kept;
        } catch (IntegrationError& e) {
          if (e.raw_partial) kept.t = e.raw_partial->t;
          e.raw_partial = std::make_shared<const RawTrajectory>(std::move(kept));
          throw;
        }
      },
      observe);
}

}  // namespace condyn
