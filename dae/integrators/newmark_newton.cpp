#include "dae/integrators/newmark_newton.hpp"

#include "dae/linsolve/kkt.hpp"

namespace condyn {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

/// S += s B, B skipped when it vanishes identically (0 x 0): the sum's pattern is the union of
/// the stored patterns, fixed as each block's is.
void add_scaled(Sparse& S, const Sparse& B, double s) {
  if (B.rows() == S.rows() && B.cols() == S.cols()) S += s * B;
}

}  // namespace

NewmarkNewton::NewmarkNewton(MechanicalSystem& system, bool linear)
    : system_(system),
      linear_(linear),
      n_(system.dofs()),
      m_(system.constraints()),
      velocity_rows_(Eigen::VectorXd::Zero(system.constraints())) {
  const std::vector<bool>& position = system.position_rows();
  for (int i = 0; i < m_; ++i) velocity_rows_[i] = position[static_cast<std::size_t>(i)] ? 0 : 1;
}

void NewmarkNewton::residual(double t, const StepState& x, const StepCoefficients& c,
                             Eigen::VectorXd& out) {
  ++residuals_;
  out.resize(n_ + m_);
  f_.resize(n_);
  system_.force(t, x.u, x.v, f_);
  auto r = out.head(n_);
  r = system_.mass(t, x.u) * x.acc - f_;
  if (m_ > 0) r += system_.constraint_jacobian(t, x.u).transpose() * x.lambda;
  r /= c.beta_prime;
  if (m_ == 0) return;
  phi_.resize(m_);
  psi_.resize(m_);
  system_.position_residual(t, x.u, phi_);
  if (velocity_rows_.any()) {
    system_.velocity_residual(t, x.u, x.v, psi_);
    phi_ += velocity_rows_.cwiseProduct(psi_) / c.gamma_prime;
  }
  out.tail(m_) = phi_;
}

Sparse NewmarkNewton::momentum_block(double t, const StepState& x, const StepCoefficients& c) {
  Sparse S = system_.mass(t, x.u);
  const double s = 1.0 / c.beta_prime;
  add_scaled(S, system_.stiffness(t, x.u, x.v), s);
  add_scaled(S, system_.damping(t, x.u, x.v), c.gamma_prime * s);
  if (!linear_) {
    add_scaled(S, system_.mass_jacobian(t, x.u, x.acc), s);
    if (m_ > 0) add_scaled(S, system_.constraint_force_jacobian(t, x.u, x.lambda), s);
  }
  return S;
}

Sparse NewmarkNewton::constraint_block(double t, const StepState& x, const StepCoefficients& c) {
  Sparse B = system_.constraint_jacobian(t, x.u);
  if (velocity_rows_.any()) {
    const Sparse& psi_u = system_.velocity_residual_jacobian(t, x.u, x.v);
    if (psi_u.rows() == m_ && psi_u.cols() == n_) {
      const Sparse on_velocity_rows = velocity_rows_.asDiagonal() * psi_u;
      B += (1.0 / c.gamma_prime) * on_velocity_rows;
    }
  }
  return B;
}

Eigen::VectorXd NewmarkNewton::row_sensitivities(double t, const StepState& x,
                                                 const StepCoefficients& c) {
  Eigen::VectorXd out(n_ + m_);
  out.head(n_) = absolute_row_sums(momentum_block(t, x, c), n_);
  if (m_ > 0) out.tail(m_) = absolute_row_sums(constraint_block(t, x, c), n_);
  return out;
}

void NewmarkNewton::apply(double /*t*/, const Eigen::VectorXd& d, const StepCoefficients& c,
                          StepState& x) {
  const auto du = d.head(n_);
  x.u += du;
  x.v += c.gamma_prime * du;
  x.acc += c.beta_prime * du;
  x.lambda += c.beta_prime * d.tail(m_);
}

bool NewmarkNewton::factor(double t, const StepState& x, const StepCoefficients& c) {
  if (keeps_factors(linear_, c)) return true;
  const Sparse S = momentum_block(t, x, c);
  Sparse matrix;
  if (m_ > 0) {
    const Sparse A = system_.constraint_jacobian(t, x.u);
    matrix = kkt_matrix(S, A, constraint_block(t, x, c));
  } else {
    matrix = S;
    matrix.makeCompressed();
  }
  nonzeros_ = matrix.nonZeros();
  ++factorizations_;
  return record_factors(klu_.factor(matrix), c);
}

}  // namespace condyn
