#include "dae/formulations/projected_ode.hpp"

#include "dae/interface/recoverable_error.hpp"

#include "dae/formulations/kkt_newton.hpp"
#include "dae/linsolve/kkt.hpp"
#include "models/core/row_scales.hpp"

#include <limits>
#include <sstream>
#include <stdexcept>

namespace condyn {

namespace {

// Gauss-Newton iterations of the position projection for nonlinear constraints. Convergence is
// quadratic from a state one integration step off the manifold; more than a few iterations
// means the state has left the region where the projection is meaningful.
constexpr int kMaxProjectionIterations = 10;

}  // namespace

ProjectedOde::ProjectedOde(const MechanicalSystem& system, const Eigen::VectorXd& u0, bool linear,
                           const Model* loads)
    : system_(system.clone()),
      observer_(system.clone()),
      n_(system.dofs()),
      m_(system.constraints()),
      varying_(system.has_curvature()),
      linear_(linear),
      held_(linear ? held_massless_of(system) : nullptr),
      loads_(loads) {
  for (int i = 0; i < m_; ++i) {
    if (system.position_rows()[static_cast<std::size_t>(i)]) position_rows_.push_back(i);
  }
  select_p_.resize(static_cast<Eigen::Index>(position_rows_.size()), m_);
  for (std::size_t k = 0; k < position_rows_.size(); ++k) {
    select_p_.insert(static_cast<Eigen::Index>(k), position_rows_[k]) = 1.0;
  }
  force_.resize(n_);
  rows_.resize(m_);
  try {
    factor(0.0, u0, constant_);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
}

void ProjectedOde::factor(double t, const ConstRef& u, Factors& f) const {
  Eigen::SparseMatrix<double> M = system_->mass(t, u);
  // A held massless DOF's row and column are empty in M and A: a unit pivot there decouples it
  // (its acceleration and corrections come from its own rows, HeldMassless).
  if (held_) {
    for (int h : held_->dofs()) M.coeffRef(h, h) = 1.0;
  }
  const Eigen::SparseMatrix<double>& A = system_->constraint_jacobian(t, u);
  f.scale = row_scales(A);
  f.A = f.scale.asDiagonal() * A;
  f.Ap = select_p_ * f.A;
  for (auto [lu, B] : {std::pair{&f.kkt, &f.A}, std::pair{&f.kkt_p, &f.Ap}}) {
    if (B == &f.Ap && position_rows_.empty()) break;  // no position projection
    lu->restart();                                    // pivots chosen at this state
    if (!lu->factor(kkt_matrix(M, *B))) {
      std::ostringstream s;
      s << "the KKT system [M Aᵀ; A 0] is singular at t = " << t
        << " (a DOF without mass that no constraint fixes, dependent constraints, or a singular "
           "configuration)";
      throw RecoverableError(s.str());  // at a trial state: a smaller step may avoid it
    }
  }
}

const ProjectedOde::Factors& ProjectedOde::factors(double t, const ConstRef& u) const {
  if (!varying_) return constant_;
  factor(t, u, scratch_);
  return scratch_;
}

Eigen::VectorXd ProjectedOde::correction(const FixedPatternKlu& kkt,
                                         const Eigen::VectorXd& r) const {
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n_ + r.size());
  rhs.tail(r.size()) = -r;
  return kkt.solve(rhs).head(n_);
}

Eigen::VectorXd ProjectedOde::accelerations(MechanicalSystem& loads_from, double t,
                                            const ConstRef& u, const ConstRef& v) const {
  const Factors& f = factors(t, u);
  loads_from.force(t, u, v, force_);
  Eigen::VectorXd rhs(n_ + m_);
  rhs.head(n_) = force_;
  if (m_ > 0) {
    system_->acceleration_bias(t, u, v, rows_);
    rhs.tail(m_) = f.scale.cwiseProduct(rows_);
  }
  if (held_) {
    for (int h : held_->dofs()) rhs[h] = 0.0;
  }
  Eigen::VectorXd x = f.kkt.solve(rhs);
  x.tail(m_) = f.scale.cwiseProduct(x.tail(m_));  // λ in the rows' own units
  if (held_) {
    Eigen::VectorXd a = x.head(n_);
    held_->accelerations(v, loads().applied_forces_derivative(1, t),
                         loads().applied_forces_derivative(2, t), a);
    x.head(n_) = a;
  }
  return x;
}

const Model& ProjectedOde::loads() const {
  if (loads_ == nullptr) {
    throw std::logic_error("ProjectedOde: massless DOFs held by stiffness need the model's loads");
  }
  return *loads_;
}

void ProjectedOde::settle_held(double t, Ref u, Ref v) const {
  if (!held_) return;
  Eigen::VectorXd uu = u, vv = v;
  held_->settle(loads().applied_forces(t, segment_start_), loads().applied_forces_derivative(1, t),
                uu, vv);
  u = uu;
  v = vv;
}

void ProjectedOde::settle(double t, Eigen::VectorXd& y) const {
  // A drive's table changes its rate at a sample (Model::breakpoints): v moves onto the velocity
  // rows at t by the least change of kinetic energy, as project() moves it after every step.
  if (varying_ && m_ > 0) {
    const Factors& f = factors(t, y.head(n_));
    system_->velocity_residual(t, y.head(n_), y.tail(n_), rows_);
    y.tail(n_) += correction(f.kkt, f.scale.cwiseProduct(rows_));
  }
  settle_held(t, y.head(n_), y.tail(n_));
}

void ProjectedOde::rhs(double t, ConstRef y, Ref ydot) const {
  ydot.head(n_) = y.tail(n_);
  ydot.tail(n_) = accelerations(*system_, t, y.head(n_), y.tail(n_)).head(n_);
}

Eigen::VectorXd ProjectedOde::multipliers(double t, const Eigen::VectorXd& y) const {
  return accelerations(*observer_, t, y.head(n_), y.tail(n_)).tail(m_);
}

bool ProjectedOde::project(double t, ConstRef y, Ref corr, const Eigen::VectorXd& settled) const {
  corr.setZero();
  bool converged = position_rows_.empty() || !varying_;
  Eigen::VectorXd u = y.head(n_);
  const Factors* f = &factors(t, u);
  if (!position_rows_.empty()) {
    double previous = std::numeric_limits<double>::infinity();
    for (int it = 0; it < kMaxProjectionIterations; ++it) {
      system_->position_residual(t, u, rows_);
      const Eigen::VectorXd du = correction(f->kkt_p, select_p_ * f->scale.cwiseProduct(rows_));
      u += du;
      if (varying_) f = &factors(t, u);
      if (!varying_) break;
      const double size = du.lpNorm<Eigen::Infinity>();
      // At roundoff of the displacements; or at roundoff of the coordinates, where the
      // corrections stop shrinking (a member of length 300 holds |x2 − x1| to 6e-14, and a
      // pendulum of that length stalled at t = 7e-4 with 10⁵ refused projections, ever smaller
      // steps): then within the error test's tolerance.
      if (size <= 1e-14 * (1.0 + u.lpNorm<Eigen::Infinity>()) ||
          (size > 0.5 * previous && (du.array().abs() <= settled.head(n_).array()).all())) {
        converged = true;
        break;
      }
      previous = size;
    }
  }
  Eigen::VectorXd v = y.tail(n_);
  if (m_ > 0) {
    system_->velocity_residual(t, u, v, rows_);
    v += correction(f->kkt, f->scale.cwiseProduct(rows_));
  }
  settle_held(t, u, v);  // after the rows on the DOFs with mass, which the held rows read
  corr.head(n_) = u - y.head(n_);
  corr.tail(n_) = v - y.tail(n_);
  last_ = f;
  return converged;
}

void ProjectedOde::project_error(Ref err) const {
  const Factors& f = last_ != nullptr ? *last_ : constant_;
  if (!position_rows_.empty()) {
    err.head(n_) += correction(f.kkt_p, f.Ap * err.head(n_));
  }
  if (m_ > 0) err.tail(n_) += correction(f.kkt, f.A * err.tail(n_));
  if (held_) {
    // The held rows linearised: the held DOFs' errors follow the others' as their rows say.
    Eigen::VectorXd eu = err.head(n_), ev = err.tail(n_);
    const Eigen::VectorXd none = Eigen::VectorXd::Zero(n_);
    held_->settle(none, none, eu, ev);
    err << eu, ev;
  }
}

std::unique_ptr<NewtonSystem> ProjectedOde::newton_system() const {
  if (linear_) return std::make_unique<KktNewton>(linear_matrices(*system_), held_);
  // The run's evaluator, in the run's segment; a and λ as the right-hand side computes them.
  return std::make_unique<KktNewton>(*system_,
                                     [this](double t, const ConstRef& u, const ConstRef& v) {
                                       return accelerations(*system_, t, u, v);
                                     });
}

}  // namespace condyn
