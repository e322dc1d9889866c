#include "dae/integrators/stabilized_newmark_newton.hpp"

#include <algorithm>
#include <vector>

namespace condyn {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

/// Whether a block a MechanicalSystem reports is there (an empty 0 x 0 one vanishes identically).
bool present(const Sparse& B, Eigen::Index rows, Eigen::Index cols) {
  return B.rows() == rows && B.cols() == cols;
}

/// One block of a larger matrix, at its row and column offsets.
struct Placed {
  const Sparse* block;
  Eigen::Index row, col;
};

/// The matrix of `size` holding each block at its place, every stored entry kept (explicit
/// zeros too: the pattern must not depend on the values, KLU reuses its analysis).
Sparse assemble(Eigen::Index size, const std::vector<Placed>& blocks) {
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::Index count = 0;
  for (const Placed& b : blocks) count += b.block->nonZeros();
  entries.reserve(static_cast<std::size_t>(count));
  for (const Placed& b : blocks) {
    for (Eigen::Index j = 0; j < b.block->outerSize(); ++j) {
      for (Sparse::InnerIterator it(*b.block, j); it; ++it) {
        entries.emplace_back(b.row + it.row(), b.col + it.col(), it.value());
      }
    }
  }
  Sparse out(size, size);
  out.setFromTriplets(entries.begin(), entries.end());
  out.makeCompressed();
  return out;
}

bool has_position_rows(const MechanicalSystem& system) {
  const auto& position = system.position_rows();
  return std::find(position.begin(), position.end(), true) != position.end();
}

}  // namespace

StabilizedNewmarkNewton::StabilizedNewmarkNewton(MechanicalSystem& system, bool linear)
    : system_(system),
      index3_(system, linear),
      linear_(linear),
      n_(system.dofs()),
      m_(system.constraints()),
      mp_(0),
      velocity_rows_(Eigen::VectorXd::Zero(system.constraints())) {
  const std::vector<bool>& position = system.position_rows();
  std::vector<Eigen::Triplet<double>> picked;
  for (int i = 0; i < m_; ++i) {
    if (position[static_cast<std::size_t>(i)]) {
      picked.emplace_back(mp_++, i, 1.0);
    } else {
      velocity_rows_[i] = 1.0;
    }
  }
  pick_.resize(mp_, m_);
  pick_.setFromTriplets(picked.begin(), picked.end());
}

void StabilizedNewmarkNewton::begin_step(StepState& x) {
  x.mu = Eigen::VectorXd::Zero(mp_);
  w_ = x.u;
}

void StabilizedNewmarkNewton::residual(double t, const StepState& x, const StepCoefficients& c,
                                       Eigen::VectorXd& out) {
  index3_.residual(t, x, c, out);
  if (mp_ == 0) return;
  psi_.resize(m_);
  system_.velocity_residual(t, x.u, x.v, psi_);
  out.conservativeResize(n_ + m_ + mp_);
  out.tail(mp_) = (pick_ * psi_) / c.gamma_prime;
}

Eigen::VectorXd StabilizedNewmarkNewton::newmark_displacement(double t, const StepState& x) {
  if (mp_ == 0) return x.u;
  return x.u - system_.constraint_jacobian(t, x.u).transpose() * (pick_.transpose() * x.mu);
}

void StabilizedNewmarkNewton::return_to(double t, const StepState& x) {
  w_ = newmark_displacement(t, x);
}

void StabilizedNewmarkNewton::apply(double t, const Eigen::VectorXd& d, const StepCoefficients& c,
                                    StepState& x) {
  x.u += d.head(n_);
  x.lambda += c.beta_prime * d.segment(n_, m_);
  x.mu += d.tail(mp_);
  // v and ü follow w, which follows u and μ exactly: the step's formulas hold at every iterate.
  Eigen::VectorXd w = newmark_displacement(t, x);
  const Eigen::VectorXd dw = w - w_;
  x.v += c.gamma_prime * dw;
  x.acc += c.beta_prime * dw;
  w_ = std::move(w);
}

Sparse StabilizedNewmarkNewton::matrix(double t, const StepState& x, const StepCoefficients& c) {
  Sparse S = index3_.momentum_block(t, x, c);
  Sparse B = index3_.constraint_block(t, x, c);
  const Sparse A = system_.constraint_jacobian(t, x.u);
  // M + (γ'/β') C: how the momentum rows move with w.
  Sparse inertia = system_.mass(t, x.u);
  const Sparse& C = system_.damping(t, x.u, x.v);
  if (present(C, n_, n_)) inertia += (c.gamma_prime / c.beta_prime) * C;
  const Sparse Ap = pick_ * A;
  const Sparse ApT = Ap.transpose();
  // The ψ_p rows in Δu: P (ψ_u / γ' + A).
  Sparse Z = Ap;
  const Sparse& psi_u = system_.velocity_residual_jacobian(t, x.u, x.v);
  if (present(psi_u, m_, n_)) Z += (1.0 / c.gamma_prime) * (pick_ * psi_u);
  const bool velocity_rows = velocity_rows_.any();
  const Sparse Av = velocity_rows_.asDiagonal() * A;
  // H = ∂(A_pᵀ μ)/∂u, where the rows curve: Δw = (I − H) Δu − A_pᵀ Δμ.
  if (!linear_) {
    const Eigen::VectorXd mu_rows = pick_.transpose() * x.mu;
    const Sparse H = system_.constraint_force_jacobian(t, x.u, mu_rows);
    if (present(H, n_, n_)) {
      S -= inertia * H;
      if (velocity_rows) B -= Av * H;
      Z -= Ap * H;
    }
  }
  const Sparse At = A.transpose();
  const Sparse X = -(inertia * ApT);
  const Sparse W = -(Ap * ApT);
  std::vector<Placed> blocks = {{&S, 0, 0},  {&At, 0, n_},     {&X, 0, n_ + m_},
                                {&B, n_, 0}, {&Z, n_ + m_, 0}, {&W, n_ + m_, n_ + m_}};
  Sparse Y;
  if (velocity_rows) {
    Y = -(Av * ApT);
    blocks.push_back({&Y, n_, n_ + m_});
  }
  return assemble(n_ + m_ + mp_, blocks);
}

bool StabilizedNewmarkNewton::factor(double t, const StepState& x, const StepCoefficients& c) {
  if (keeps_factors(linear_, c)) return true;
  const Sparse K = matrix(t, x, c);
  nonzeros_ = K.nonZeros();
  ++factorizations_;
  return record_factors(klu_.factor(K), c);
}

StabilizedSize stabilized_size(MechanicalSystem& system, bool linear, double t0,
                               const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  if (!has_position_rows(system)) return {};
  StabilizedNewmarkNewton newton(system, linear);
  StepState x{u, v, Eigen::VectorXd::Zero(u.size()), Eigen::VectorXd::Zero(system.constraints()),
              Eigen::VectorXd()};
  newton.begin_step(x);
  return {newton.mu_size(), newton.matrix(t0, x, {1.0, 1.0}).nonZeros()};
}

std::unique_ptr<StepNewton> make_step_newton(MechanicalSystem& system, bool linear,
                                             NewmarkConstraints form) {
  // Without position rows there is nothing to stabilize: every row is held at velocity level.
  if (form == NewmarkConstraints::stabilized && has_position_rows(system)) {
    return std::make_unique<StabilizedNewmarkNewton>(system, linear);
  }
  return std::make_unique<NewmarkNewton>(system, linear);
}

}  // namespace condyn
