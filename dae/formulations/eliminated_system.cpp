// The mixed formulation's reduced system (dae/formulations/eliminated_system.hpp).

#include "dae/formulations/eliminated_system.hpp"

#include <stdexcept>

namespace condyn {

EliminatedSystem::EliminatedSystem(const Model& model, const ConstraintTreatment& treatment)
    : full_(model.evaluator()) {
  auto d = std::make_shared<Data>();
  d->T = treatment.transform.T;
  d->Tt = d->T.transpose();
  d->G = treatment.transform.G;
  d->masters = treatment.transform.masters;
  d->kept = treatment.kept;
  d->eliminated = treatment.eliminated;
  d->m = model.constraint_count();
  const auto& position = full_->position_rows();
  std::vector<Eigen::Triplet<double>> s, e;
  for (std::size_t k = 0; k < d->kept.size(); ++k) {
    const auto row = static_cast<std::size_t>(d->kept[k]);
    d->position.push_back(position[row]);
    s.emplace_back(static_cast<int>(k), d->kept[k], 1.0);
  }
  d->S.resize(static_cast<Eigen::Index>(d->kept.size()), d->m);
  d->S.setFromTriplets(s.begin(), s.end());
  for (std::size_t k = 0; k < d->eliminated.size(); ++k) {
    const Constraint& c = model.constraints[static_cast<std::size_t>(d->eliminated[k])];
    d->g.push_back(c.position_value);
    d->rheonomic = d->rheonomic || !c.position_value.is_zero();
    for (const auto& [dof, a] : c.coefficients) e.emplace_back(static_cast<int>(k), dof, a);
  }
  d->Ae.resize(static_cast<Eigen::Index>(d->eliminated.size()), model.dofs());
  d->Ae.setFromTriplets(e.begin(), e.end());
  if (!d->eliminated.empty()) {
    d->aat.compute(Sparse(d->Ae * d->Ae.transpose()));
    if (d->aat.info() != Eigen::Success) {
      throw std::invalid_argument("the eliminated constraints are rank deficient");
    }
  }
  data_ = d;
  const auto n = static_cast<Eigen::Index>(model.dofs());
  u_.setZero(n);
  v_.setZero(n);
  f_.setZero(n);
  rows_.setZero(d->m);
  if (!model.is_nonlinear()) {
    // Constant M, K, C, A: the reduced blocks once, for every clone (at any state: u_ = 0).
    d->M = d->Tt * full_->mass(0.0, u_) * d->T;
    d->K = d->Tt * full_->stiffness(0.0, u_, v_) * d->T;
    d->C = d->Tt * full_->damping(0.0, u_, v_) * d->T;
    d->A = d->S * full_->constraint_jacobian(0.0, u_) * d->T;
    d->constant = true;
  } else {
    // State-dependent blocks, mapped at every evaluation: product plans made once.
    mass_ = stiffness_ = damping_ = mass_jacobian_ = constraint_force_jacobian_ =
        FixedProduct(d->Tt, d->T);
    a_ = constraint_product_jacobian_ = velocity_residual_jacobian_ = bias_jacobian_u_ =
        bias_jacobian_v_ = FixedProduct(d->S, d->T);
  }
}

EliminatedSystem::EliminatedSystem(const EliminatedSystem& other)
    : MechanicalSystem(other),
      data_(other.data_),
      full_(other.full_->clone()),
      u_(other.u_),
      v_(other.v_),
      f_(other.f_),
      rows_(other.rows_),
      mass_(other.mass_),
      stiffness_(other.stiffness_),
      damping_(other.damping_),
      a_(other.a_),
      mass_jacobian_(other.mass_jacobian_),
      constraint_force_jacobian_(other.constraint_force_jacobian_),
      constraint_product_jacobian_(other.constraint_product_jacobian_),
      velocity_residual_jacobian_(other.velocity_residual_jacobian_),
      bias_jacobian_u_(other.bias_jacobian_u_),
      bias_jacobian_v_(other.bias_jacobian_v_) {}

Eigen::VectorXd EliminatedSystem::lifted(int order, double t) const {
  const Data& d = *data_;
  Eigen::VectorXd g(static_cast<Eigen::Index>(d.g.size()));
  for (std::size_t k = 0; k < d.g.size(); ++k)
    g[static_cast<Eigen::Index>(k)] = d.g[k].derivative(order, t, steps_at(t));
  return d.G * g;
}

void EliminatedSystem::at(double t, const ConstRef& q) {
  full_->begin_segment(steps_at(t));
  u_.noalias() = data_->T * q;
  if (data_->rheonomic) u_ += lifted(0, t);
}

void EliminatedSystem::at(double t, const ConstRef& q, const ConstRef& w) {
  at(t, q);
  v_.noalias() = data_->T * w;
  if (data_->rheonomic) v_ += lifted(1, t);
}

void EliminatedSystem::select(const Eigen::VectorXd& x, Ref out) const {
  for (std::size_t k = 0; k < data_->kept.size(); ++k)
    out[static_cast<Eigen::Index>(k)] = x[data_->kept[k]];
}

Eigen::VectorXd EliminatedSystem::restrict(const Eigen::VectorXd& x) const {
  Eigen::VectorXd q(static_cast<Eigen::Index>(data_->masters.size()));
  for (std::size_t k = 0; k < data_->masters.size(); ++k)
    q[static_cast<Eigen::Index>(k)] = x[data_->masters[k]];
  return q;
}

std::pair<Eigen::VectorXd, Eigen::VectorXd> EliminatedSystem::expand(double t, const ConstRef& q,
                                                                     const ConstRef& w) const {
  Eigen::VectorXd u = data_->T * q, v = data_->T * w;
  if (data_->rheonomic) {
    u += lifted(0, t);
    v += lifted(1, t);
  }
  return {u, v};
}

const EliminatedSystem::Sparse& EliminatedSystem::mass(double t, ConstRef q) {
  if (data_->constant) return data_->M;
  at(t, q);
  return mass_(full_->mass(t, u_));
}

void EliminatedSystem::force(double t, ConstRef q, ConstRef w, Ref f) {
  at(t, q, w);
  full_->force(t, u_, v_, f_);
  if (data_->rheonomic) f_ -= full_->mass(t, u_) * lifted(2, t);
  f.noalias() = data_->Tt * f_;
}

const EliminatedSystem::Sparse& EliminatedSystem::stiffness(double t, ConstRef q, ConstRef w) {
  if (data_->constant) return data_->K;
  at(t, q, w);
  block_ = full_->stiffness(t, u_, v_);
  if (data_->rheonomic) {
    const Sparse& mj = full_->mass_jacobian(t, u_, lifted(2, t));
    if (mj.size() > 0) block_ += mj;  // −d(f − M G g'')/du = K + d(M a)/du at a = G g''
  }
  return stiffness_(block_);
}

const EliminatedSystem::Sparse& EliminatedSystem::damping(double t, ConstRef q, ConstRef w) {
  if (data_->constant) return data_->C;
  at(t, q, w);
  return damping_(full_->damping(t, u_, v_));
}

const EliminatedSystem::Sparse& EliminatedSystem::constraint_jacobian(double t, ConstRef q) {
  if (data_->constant) return data_->A;
  at(t, q);
  return a_(full_->constraint_jacobian(t, u_));
}

void EliminatedSystem::position_residual(double t, ConstRef q, Ref phi) {
  at(t, q);
  full_->position_residual(t, u_, rows_);
  select(rows_, phi);
}

void EliminatedSystem::velocity_residual(double t, ConstRef q, ConstRef w, Ref psi) {
  at(t, q, w);
  full_->velocity_residual(t, u_, v_, rows_);
  select(rows_, psi);
}

void EliminatedSystem::acceleration_bias(double t, ConstRef q, ConstRef w, Ref gamma) {
  at(t, q, w);
  full_->acceleration_bias(t, u_, v_, rows_);
  if (data_->rheonomic) rows_ -= full_->constraint_jacobian(t, u_) * lifted(2, t);
  select(rows_, gamma);
}

const EliminatedSystem::Sparse& EliminatedSystem::mass_jacobian(double t, ConstRef q, ConstRef a) {
  at(t, q);
  const Eigen::VectorXd full_a = data_->T * a;
  const Sparse& mj = full_->mass_jacobian(t, u_, full_a);
  if (mj.size() == 0) return empty();
  return mass_jacobian_(mj);
}

const EliminatedSystem::Sparse& EliminatedSystem::constraint_force_jacobian(double t, ConstRef q,
                                                                            ConstRef w) {
  at(t, q);
  const Eigen::VectorXd full_w = data_->S.transpose() * w;
  const Sparse& j = full_->constraint_force_jacobian(t, u_, full_w);
  if (j.size() == 0) return empty();
  return constraint_force_jacobian_(j);
}

const EliminatedSystem::Sparse& EliminatedSystem::constraint_product_jacobian(double t, ConstRef q,
                                                                              ConstRef a) {
  at(t, q);
  const Eigen::VectorXd full_a = data_->T * a;
  const Sparse& j = full_->constraint_product_jacobian(t, u_, full_a);
  if (j.size() == 0) return empty();
  return constraint_product_jacobian_(j);
}

const EliminatedSystem::Sparse& EliminatedSystem::velocity_residual_jacobian(double t, ConstRef q,
                                                                             ConstRef w) {
  at(t, q, w);
  const Sparse& j = full_->velocity_residual_jacobian(t, u_, v_);
  if (j.size() == 0) return empty();
  return velocity_residual_jacobian_(j);
}

const EliminatedSystem::Sparse& EliminatedSystem::acceleration_bias_jacobian_u(double t, ConstRef q,
                                                                               ConstRef w) {
  at(t, q, w);
  Sparse j = full_->acceleration_bias_jacobian_u(t, u_, v_);
  if (data_->rheonomic) {
    // γ̂ holds −A_k(u) G g_e'': its derivative is −d(A(u) a)/du at a = G g_e''.
    const Sparse& cp = full_->constraint_product_jacobian(t, u_, lifted(2, t));
    if (cp.size() > 0) j = j.size() > 0 ? Sparse(j - cp) : Sparse(-cp);
  }
  if (j.size() == 0) return empty();
  return bias_jacobian_u_(j);
}

const EliminatedSystem::Sparse& EliminatedSystem::acceleration_bias_jacobian_v(double t, ConstRef q,
                                                                               ConstRef w) {
  at(t, q, w);
  const Sparse& j = full_->acceleration_bias_jacobian_v(t, u_, v_);
  if (j.size() == 0) return empty();
  return bias_jacobian_v_(j);
}

std::optional<double> EliminatedSystem::energy(double t, ConstRef q, ConstRef w) {
  at(t, q, w);
  return full_->energy(t, u_, v_);
}

Eigen::VectorXd EliminatedSystem::multipliers(double t, const ConstRef& q, const ConstRef& w,
                                              const ConstRef& qdd, const ConstRef& lambda_kept) {
  const Data& d = *data_;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(d.m);
  for (std::size_t k = 0; k < d.kept.size(); ++k)
    lambda[d.kept[k]] = lambda_kept[static_cast<Eigen::Index>(k)];
  if (d.eliminated.empty()) return lambda;
  at(t, q, w);
  Eigen::VectorXd a = d.T * qdd;
  if (d.rheonomic) a += lifted(2, t);
  // A_eᵀ λ_e = f − M u'' − A_kᵀ λ_k (M u'' = f − Aᵀ λ).
  full_->force(t, u_, v_, f_);
  f_ -= full_->mass(t, u_) * a;
  if (!d.kept.empty()) f_ -= full_->constraint_jacobian(t, u_).transpose() * lambda;
  const Eigen::VectorXd rhs = d.Ae * f_;
  const Eigen::VectorXd lambda_e = d.aat.solve(rhs);
  for (std::size_t k = 0; k < d.eliminated.size(); ++k)
    lambda[d.eliminated[k]] = lambda_e[static_cast<Eigen::Index>(k)];
  return lambda;
}

}  // namespace condyn
