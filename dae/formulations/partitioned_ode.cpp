// Coordinate partitioning's ODE (dae/formulations/partitioned_ode.hpp).

#include "dae/formulations/partitioned_ode.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "dae/interface/recoverable_error.hpp"
#include "dae/interface/scheme_not_applicable.hpp"
#include "models/core/row_scales.hpp"

namespace condyn {

namespace {

/// The Newton iteration stops once its correction is this many ulps of the coordinates' size
/// even when the tolerance asks for less: below it the corrections are roundoff.
constexpr double kRoundoffUlps = 16.0;
/// A stalled iteration's correction is accepted up to this multiple of the tolerance: 1e3, the
/// inverse of elimination_run.cpp's margin, so up to the run's displacement atol.
constexpr double kStallAccepted = 1e3;

/// The rows with no position form, refused; empty when every row has one.
std::string rows_without_position_form(const Model& model) {
  const auto& position = model.system->position_rows();
  std::string names;
  for (std::size_t i = 0; i < model.constraints.size(); ++i) {
    const Constraint& c = model.constraints[i];
    if (position[i] || (!c.nonholonomic && !c.coefficients.empty())) continue;
    names += (names.empty() ? "'" : ", '") + c.name + "'";
  }
  return names;
}

/// The DOFs of `a` not in `b` (both ascending).
std::vector<int> minus(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

}  // namespace

PartitionedOde::PartitionedOde(const Model& model, double t0)
    : model_(model),
      system_(model.evaluator()),
      n_(model.dofs()),
      m_(model.constraint_count()),
      ni_(0) {
  if (const std::string names = rows_without_position_form(model); !names.empty()) {
    throw SchemeNotApplicable(
        "elimination by coordinate partitioning solves the constraints for the dependent "
        "coordinates at every evaluation, and the velocity-level rows " +
        names +
        " have no position form to solve (nonholonomic: they integrate to no constraint on "
        "the coordinates). The chapter says so: nonholonomic MFCs \"are non treatable by "
        "master-slave methods unless they integrate to holonomic constraints\" (§5.6). Use a "
        "multiplier scheme (ggl, index1) or projection");
  }
  const auto& position = system_->position_rows();
  for (int i = 0; i < m_; ++i) {
    if (!position[static_cast<std::size_t>(i)]) integrable_velocity_rows_.push_back(i);
  }
  u_ = model.u0;
  v_ = model.v0;
  system_->begin_segment(t0);
  try {
    a_ = system_->constraint_jacobian(t0, u_);
    adopt(choose_partition(a_), t0);
  } catch (const std::invalid_argument& why) {
    throw SchemeNotApplicable(std::string("elimination by coordinate partitioning needs "
                                          "independent constraint rows at the start: ") +
                              why.what());
  }
  // ni_ = 0: the constraints fix every coordinate (a fully driven mechanism): nothing is
  // integrated, and full() gives the kinematics (positions by Newton, velocities and
  // accelerations from the rows) and the reactions (the KKT system) at each time the loop visits.
  ni_ = static_cast<int>(partition_.independent.size());
  if (!factor_dependent(t0)) {
    throw SchemeNotApplicable(
        "elimination by coordinate partitioning: the dependent block of the constraint "
        "Jacobian is singular at the start");
  }
  try {
    accelerations(t0);
  } catch (const RecoverableError&) {
    throw SchemeNotApplicable(
        "elimination by coordinate partitioning: the system [M Aᵀ; A 0] is singular at the "
        "start (a massless DOF that no constraint fixes); the multiplier schemes treat such "
        "a model");
  }
}

PartitionedOde::~PartitionedOde() = default;

void PartitionedOde::adopt(CoordinatePartition p, double /*t*/) const {
  partition_ = std::move(p);
  ad_ = a_ * partition_.select_dependent;
  ad_.makeCompressed();
  if (m_ > 0) lu_.analyzePattern(ad_);
  reference_quality_ = partition_quality(a_, partition_);
}

void PartitionedOde::constraints_at(double t) const {
  phi_.resize(m_);
  system_->position_residual(t, u_, phi_);
  for (int i : integrable_velocity_rows_) {
    const Constraint& c = model_.constraints[static_cast<std::size_t>(i)];
    double au = 0.0;
    for (const auto& [d, a] : c.coefficients) au += a * u_[d];
    phi_[i] = au - c.position_value.value(t);
  }
}

bool PartitionedOde::factor_dependent(double t) const {
  if (m_ == 0) return true;
  a_ = system_->constraint_jacobian(t, u_);
  ad_ = a_ * partition_.select_dependent;
  ad_.makeCompressed();
  lu_.factorize(ad_);
  return lu_.info() == Eigen::Success;
}

void PartitionedOde::solve_positions(double t, const ConstRef& q) const {
  for (int k = 0; k < ni_; ++k) u_[partition_.independent[static_cast<std::size_t>(k)]] = q[k];
  if (m_ == 0) return;
  const double scale = std::max(u_.lpNorm<Eigen::Infinity>(), system_->coordinate_scale());
  const double floor = kRoundoffUlps * std::numeric_limits<double>::epsilon() * scale;
  const double tolerance = std::max(tolerance_, floor);
  double last = INFINITY, before = INFINITY;
  for (int it = 0;; ++it) {
    // A at the current u: after the last correction it serves the velocities and the KKT system.
    if (!factor_dependent(t)) throw RecoverableError("coordinate partitioning: A_d is singular");
    if (it > 0 && last <= tolerance) return;
    // Corrections that no longer halve have reached the roundoff A_d's conditioning allows (above
    // the floor near a singular position, or on rigid bodies' rotation coordinates): accepted
    // while below what the error test accepts of a coordinate, kStallAccepted × the tolerance
    // (the run's atol).
    if (it > 1 && last > 0.5 * before && last <= kStallAccepted * tolerance) return;
    if (it == kMaxNewtonIterations) {
      std::ostringstream s;
      s << "coordinate partitioning: the dependent coordinates' Newton iteration did not "
           "converge at t = "
        << t << " (last correction " << last << ", tolerance " << tolerance << ")";
      throw RecoverableError(s.str());
    }
    constraints_at(t);
    const Eigen::VectorXd step = lu_.solve(-phi_);
    if (!step.allFinite()) throw RecoverableError("coordinate partitioning: non-finite step");
    for (int k = 0; k < m_; ++k) u_[partition_.dependent[static_cast<std::size_t>(k)]] += step[k];
    before = last;
    last = step.lpNorm<Eigen::Infinity>();
    ++iterations_;
  }
}

void PartitionedOde::accelerations(double t) const {
  // Rows scaled by exact powers of two: the KKT pivots do not depend on a row's units.
  const Eigen::VectorXd scale = m_ > 0 ? row_scales(a_) : Eigen::VectorXd();
  const Eigen::SparseMatrix<double> scaled =
      m_ > 0 ? Eigen::SparseMatrix<double>(scale.asDiagonal() * a_)
             : Eigen::SparseMatrix<double>(0, n_);
  const Eigen::SparseMatrix<double>& mass = system_->mass(t, u_);
  force_.resize(n_);
  system_->force(t, u_, v_, force_);
  Eigen::VectorXd rhs(n_ + m_);
  rhs.head(n_) = force_;
  if (m_ > 0) {
    gamma_.resize(m_);
    system_->acceleration_bias(t, u_, v_, gamma_);
    rhs.tail(m_) = scale.cwiseProduct(gamma_);
  }
  if (!kkt_lu_.factor(kkt_matrix(mass, scaled))) {
    throw RecoverableError("coordinate partitioning: [M Aᵀ; A 0] is singular");
  }
  const Eigen::VectorXd x = kkt_lu_.solve(rhs);
  a_acc_ = x.head(n_);
  lambda_ = m_ > 0 ? Eigen::VectorXd(scale.cwiseProduct(x.tail(m_))) : Eigen::VectorXd();
}

PartitionedOde::Full PartitionedOde::full(double t, const ConstRef& y) const {
  solve_positions(t, y.head(ni_));
  for (int k = 0; k < ni_; ++k)
    v_[partition_.independent[static_cast<std::size_t>(k)]] = y[ni_ + k];
  if (m_ > 0) {
    for (int d : partition_.dependent) v_[d] = 0.0;
    psi_.resize(m_);
    system_->velocity_residual(t, u_, v_, psi_);  // ψ = A u' + b, linear in u'
    const Eigen::VectorXd vd = lu_.solve(-psi_);
    for (int k = 0; k < m_; ++k) v_[partition_.dependent[static_cast<std::size_t>(k)]] = vd[k];
  }
  accelerations(t);
  return {u_, v_, a_acc_, lambda_};
}

void PartitionedOde::precondition(double gamma, ConstRef r, Ref z) const {
  z.head(ni_) = r.head(ni_) + gamma * r.tail(ni_);
  z.tail(ni_) = r.tail(ni_);
}

void PartitionedOde::rhs(double t, ConstRef y, Ref ydot) const {
  const Full f = full(t, y);
  for (int k = 0; k < ni_; ++k) {
    const auto i = static_cast<Eigen::Index>(partition_.independent[static_cast<std::size_t>(k)]);
    ydot[k] = f.v[i];
    ydot[ni_ + k] = f.a[i];
  }
}

Eigen::VectorXd PartitionedOde::initial_state() const {
  Eigen::VectorXd y(2 * ni_);
  for (int k = 0; k < ni_; ++k) {
    const auto i = static_cast<Eigen::Index>(partition_.independent[static_cast<std::size_t>(k)]);
    y[k] = model_.u0[i];
    y[ni_ + k] = model_.v0[i];
  }
  return y;
}

bool PartitionedOde::wants_restart(double t, ConstRef y) const {
  if (m_ == 0 || ni_ == 0) return false;
  (void)full(t, y);
  const double quality = partition_quality(a_, partition_);
  if (quality >= kRepartitionFraction * reference_quality_) return false;
  std::optional<CoordinatePartition> next;
  try {
    next = choose_partition(a_);
  } catch (const std::invalid_argument&) {
    // A is rank deficient here: a singular configuration of the mechanism itself, where no
    // partition has a regular dependent block.
  }
  if (!next || next->dependent == partition_.dependent) {
    // No other partition here: keep this one, judged from now on against its quality here.
    reference_quality_ = quality;
    return false;
  }
  log_.push_back({t, minus(next->independent, partition_.independent),
                  minus(next->dependent, partition_.dependent), quality});
  pending_ = std::move(next);
  return true;
}

void PartitionedOde::settle(double t, Eigen::VectorXd& y) const {
  if (!pending_) return;
  const Full f = full(t, y);
  adopt(std::move(*pending_), t);
  pending_.reset();
  for (int k = 0; k < ni_; ++k) {
    const auto i = static_cast<Eigen::Index>(partition_.independent[static_cast<std::size_t>(k)]);
    y[k] = f.u[i];
    y[ni_ + k] = f.v[i];
  }
}

}  // namespace condyn
