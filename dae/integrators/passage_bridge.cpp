#include "dae/integrators/passage_bridge.hpp"

#include <algorithm>
#include <sstream>
#include <utility>

#include "dae/interface/singular_passage.hpp"

namespace condyn {

namespace {
/// Adds the step and evaluation counters of `from` to `to`.
void add_counters(SolveSummary& to, const SolveSummary& from) {
  to.steps += from.steps;
  to.residual_evals += from.residual_evals;
  to.jacobian_evals += from.jacobian_evals;
  to.newton_iterations += from.newton_iterations;
  to.newton_failures += from.newton_failures;
}
}  // namespace

BridgedStepper::BridgedStepper(Stepper& inner, PassageBridge bridge, int size, double t0,
                               const Eigen::VectorXd& y0)
    : inner_(inner), bridge_(std::move(bridge)), size_(size), t_last_(t0) {
  best_ = bridge_.conditioning(t0, y0);
}

Eigen::VectorXd BridgedStepper::padded(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size_);
  const Eigen::Index shared = std::min<Eigen::Index>(size_, x.size());
  y.head(shared) = x.head(shared);
  return y;
}

void BridgedStepper::begin(double t, const Eigen::VectorXd& y, bool on_failure) {
  const double h = *std::max_element(recent_.begin(), recent_.end()) / kRefinement;
  active_ = bridge_.start(t, y, h);
  active_->set_stop_time(stop_);
  const double start = bridge_.conditioning(t, y);
  exit_ = std::max(kExitGrowth * start, bridge_.exit_fraction * best_);
  done_ = false;
  passages_.push_back({t, t, h, 0, on_failure});
}

double BridgedStepper::step(double tout) {
  if (active_) {
    double t = 0.0;
    try {
      t = active_->step(tout);
    } catch (IntegrationError& e) {
      std::ostringstream s;
      s << "bridging the near-singular configuration entered at t = " << passages_.back().t_start
        << " with " << bridge_.method << " steps (h = " << passages_.back().step
        << "): " << e.what();
      IntegrationError failure(e.kind, s.str());
      failure.t_reached = e.t_reached;
      failure.last_step = e.last_step;
      throw failure;
    }
    BridgedPassage& p = passages_.back();
    ++p.steps;
    p.t_end = t;
    const double c = bridge_.conditioning(t, padded(active_->y()));
    best_ = std::max(best_, c);
    if (c >= exit_) done_ = true;
    return t;
  }
  if (pending_) {
    pending_ = false;
    begin(t_last_, inner_.y(), false);
    return step(tout);
  }
  double t = 0.0;
  try {
    t = inner_.step(tout);
  } catch (IntegrationError& e) {
    if (recent_.empty()) throw;
    // A failed step leaves IDA's and CVODE's y at the last step reached.
    const Eigen::VectorXd y = inner_.y();
    if (!(bridge_.conditioning(t_last_, y) < kFailureFraction * best_)) throw;
    begin(t_last_, y, true);
    return step(tout);
  }
  if (recent_.size() == kRecentSteps) recent_.erase(recent_.begin());
  recent_.push_back(t - t_last_);
  t_last_ = t;
  const double c = bridge_.conditioning(t, inner_.y());
  best_ = std::max(best_, c);
  pending_ = c < SingularPassage::kNearSingular * best_;
  return t;
}

void BridgedStepper::interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) {
  if (!active_) return inner_.interpolate(t, y, yp);
  Eigen::VectorXd x, xp;
  active_->interpolate(t, x, xp);
  y = padded(x);
  yp = padded(xp);
}

Eigen::VectorXd BridgedStepper::y() { return active_ ? padded(active_->y()) : inner_.y(); }

Eigen::VectorXd BridgedStepper::yp() { return active_ ? padded(active_->yp()) : inner_.yp(); }

bool BridgedStepper::wants_restart(double t) {
  return (active_ && done_) || (!active_ && inner_.wants_restart(t));
}

void BridgedStepper::restart(double t) {
  if (!active_) return inner_.restart(t);
  if (!done_) return active_->restart(t);
  // The bridge is over: the BDF integrator goes on from its last state.
  bridge_.restart_at(t, padded(active_->y()));
  SolveSummary own;
  active_->fill_summary(own);
  add_counters(bridged_, own);
  active_.reset();
  t_last_ = t;
}

void BridgedStepper::set_stop_time(double t) {
  stop_ = t;
  inner_.set_stop_time(t);
  if (active_) active_->set_stop_time(t);
}

void BridgedStepper::fill_summary(SolveSummary& summary) {
  inner_.fill_summary(summary);
  add_counters(summary, bridged_);
  if (active_) {
    SolveSummary running;
    active_->fill_summary(running);
    add_counters(summary, running);
  }
  if (passages_.empty()) return;
  constexpr std::size_t kListed = 5;
  std::ostringstream s;
  s.precision(4);
  s << "bridged " << passages_.size() << " near-singular configuration"
    << (passages_.size() == 1 ? "" : "s") << " with " << bridge_.method
    << " steps (docs/schemes.md): ";
  for (std::size_t i = 0; i < std::min(kListed, passages_.size()); ++i) {
    const BridgedPassage& p = passages_[i];
    s << (i > 0 ? ", " : "") << "t = " << p.t_start << " to " << p.t_end << " (" << p.steps
      << " steps of " << p.step << (p.on_failure ? ", after the BDF steps failed" : "") << ")";
  }
  if (passages_.size() > kListed) s << " and " << passages_.size() - kListed << " more";
  summary.add_note(RunNote::Kind::singular_passage, s.str());
}

}  // namespace condyn
