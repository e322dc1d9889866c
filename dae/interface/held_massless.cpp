// Massless DOFs held by stiffness: which they are, and their consistent values (held_massless.hpp).

#include "dae/interface/held_massless.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace condyn {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

std::shared_ptr<KktLu> factor(const Sparse& S, const char* what) {
  auto lu = std::make_shared<KktLu>();
  if (S.rows() == 0) return lu;
  lu->compute(S);
  if (lu->info() != Eigen::Success) {
    throw std::runtime_error(std::string("massless DOFs held by stiffness: ") + what +
                             " is singular (a mechanism of massless DOFs that neither stiffness, "
                             "damping nor a constraint holds)");
  }
  return lu;
}

}  // namespace

HeldMassless::HeldMassless(LinearMatrices matrices, bool consistency) : l_(std::move(matrices)) {
  HeldDofs split = held_massless_dofs(l_.M, l_.C, l_.K, l_.A);
  if (!split.coupled.empty()) {
    throw std::invalid_argument(
        "massless DOF " + std::to_string(split.coupled.front()) +
        " has damping coupling to other DOFs but no damping of its own (C_hh = 0): its row "
        "is neither algebraic nor first order");
  }
  // DOFs nothing holds are refused by the model checks; here they fail the factorization below.
  split.undamped.insert(split.undamped.end(), split.unheld.begin(), split.unheld.end());
  std::sort(split.undamped.begin(), split.undamped.end());
  undamped_ = std::move(split.undamped);
  damped_ = std::move(split.damped);
  held_ = undamped_;
  held_.insert(held_.end(), damped_.begin(), damped_.end());
  std::sort(held_.begin(), held_.end());
  if (held_.empty()) return;
  stiff_ = factor(principal_block(l_.K, undamped_), "their stiffness block K_hh");
  damp_ = factor(principal_block(l_.C, damped_), "their damping block C_hh");
  if (!consistency) return;
  const auto n = static_cast<int>(l_.M.cols());
  // X: M with the held DOFs' columns replaced by K's (undamped) or C's (damped).
  std::vector<int> kind(static_cast<std::size_t>(n), 0);  // 0 mass, 1 stiffness, 2 damping
  for (int h : undamped_) kind[static_cast<std::size_t>(h)] = 1;
  for (int h : damped_) kind[static_cast<std::size_t>(h)] = 2;
  std::vector<Eigen::Triplet<double>> trip;
  for (int j = 0; j < n; ++j) {
    const int k = kind[static_cast<std::size_t>(j)];
    const Sparse& S = k == 0 ? l_.M : (k == 1 ? l_.K : l_.C);
    for (Sparse::InnerIterator it(S, j); it; ++it)
      trip.emplace_back(static_cast<int>(it.row()), j, it.value());
  }
  Sparse X(n, n);
  X.setFromTriplets(trip.begin(), trip.end());
  kkt_ = factor(kkt_matrix(X, l_.A), "the consistency system [M Aᵀ; A 0] with their K columns");
}

void HeldMassless::mark(Eigen::VectorXd& id, Eigen::VectorXd& index) const {
  const auto n = l_.M.cols();
  for (int h : held_) id[n + h] = 0.0;
  if (index.size() == 0) index = Eigen::VectorXd::Ones(id.size());
  for (int h : undamped_) index[n + h] = std::max(index[n + h], 2.0);
}

namespace {

/// Solves S x = (b − P·a)|_dofs with a_dofs taken as 0 in the product, into a_dofs.
void solve_rows(const KktLu& lu, const Sparse& P, const std::vector<int>& dofs,
                const Eigen::VectorXd& b, Eigen::VectorXd& a) {
  if (dofs.empty()) return;
  for (int h : dofs) a[h] = 0.0;
  const Eigen::VectorXd pa = P * a;
  Eigen::VectorXd r(static_cast<Eigen::Index>(dofs.size()));
  for (std::size_t k = 0; k < dofs.size(); ++k)
    r[static_cast<Eigen::Index>(k)] = b[dofs[k]] - pa[dofs[k]];
  const Eigen::VectorXd x = lu.solve(r);
  for (std::size_t k = 0; k < dofs.size(); ++k) a[dofs[k]] = x[static_cast<Eigen::Index>(k)];
}

}  // namespace

void HeldMassless::settle(const Eigen::VectorXd& f, const Eigen::VectorXd& fdot, Eigen::VectorXd& u,
                          Eigen::VectorXd& v) const {
  solve_rows(*stiff_, l_.K, undamped_, f, u);
  if (!damped_.empty()) solve_rows(*damp_, l_.C, damped_, f - l_.K * u, v);
  solve_rows(*stiff_, l_.K, undamped_, fdot, v);
}

void HeldMassless::accelerations(const Eigen::VectorXd& v, const Eigen::VectorXd& fdot,
                                 const Eigen::VectorXd& fddot, Eigen::VectorXd& a) const {
  if (!damped_.empty()) solve_rows(*damp_, l_.C, damped_, fdot - l_.K * v, a);
  solve_rows(*stiff_, l_.K, undamped_, fddot, a);
}

Eigen::VectorXd HeldMassless::consistent(const Eigen::VectorXd& rhs, const Eigen::VectorXd& fdot,
                                         Eigen::VectorXd& u, Eigen::VectorXd& v) const {
  if (!kkt_) throw std::logic_error("HeldMassless::consistent: built without the KKT system");
  Eigen::VectorXd x = kkt_->solve(rhs);
  for (int h : undamped_) {
    u[h] += x[h];
    x[h] = 0.0;
  }
  for (int h : damped_) {
    v[h] += x[h];
    x[h] = 0.0;
  }
  // K_HuHu v_Hu = ḟ_Hu − K_Hu,rest v_rest (their rows of C are zero), then the damped rows.
  solve_rows(*stiff_, l_.K, undamped_, fdot, v);
  Eigen::VectorXd a = x.head(static_cast<Eigen::Index>(u.size()));
  if (!damped_.empty()) solve_rows(*damp_, l_.C, damped_, fdot - l_.K * v, a);
  x.head(a.size()) = a;
  return x;
}

Eigen::VectorXd held_differential_id(const HeldMassless* held, Eigen::Index size) {
  Eigen::VectorXd id = Eigen::VectorXd::Ones(size), index;
  if (held) held->mark(id, index);
  return id;
}

Eigen::VectorXd held_variable_index(const HeldMassless* held, Eigen::Index size) {
  if (!held) return {};
  Eigen::VectorXd id = Eigen::VectorXd::Ones(size), index;
  held->mark(id, index);
  return index;
}

std::shared_ptr<const HeldMassless> held_massless(const Sparse& M, const Sparse& C, const Sparse& K,
                                                  const Sparse& A, bool consistency) {
  // Every unconstrained massless DOF is held (damped or undamped), refused (coupled) or found
  // singular by the factorizations: none of them, no HeldMassless.
  if (unconstrained_massless_dofs(M, A).empty()) return nullptr;
  return std::make_shared<const HeldMassless>(LinearMatrices{M, C, K, A}, consistency);
}

std::shared_ptr<const HeldMassless> held_massless_of(const MechanicalSystem& system) {
  // The system's own constant matrices, by reference (each method's result stays valid until
  // that method is called again).
  const auto s = system.clone();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s->dofs());
  const Sparse no_rows(0, s->dofs());
  return held_massless(s->mass(0.0, zero), s->damping(0.0, zero, zero),
                       s->stiffness(0.0, zero, zero),
                       s->constraints() > 0 ? s->constraint_jacobian(0.0, zero) : no_rows);
}

std::shared_ptr<const HeldMassless> held_massless_of(const Model& model) {
  if (model.is_nonlinear()) return nullptr;
  return held_massless(model.M, model.has_damping() ? model.C : Sparse(), *model.K, model.A,
                       /*consistency=*/false);
}

}  // namespace condyn
