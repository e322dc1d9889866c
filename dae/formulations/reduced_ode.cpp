#include "dae/formulations/reduced_ode.hpp"

#include "dae/interface/scheme_not_applicable.hpp"
#include "dae/linsolve/condensed_newton.hpp"
#include "models/core/eigen_decompositions.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace condyn {

namespace {

/// Whether Ĉ = a₀ M̂ + a₁ K̂ to roundoff: Tᵀ(a₀ M + a₁ K)T and a₀ TᵀMT + a₁ TᵀKT differ only in
/// the order of their sums, each term at most a₀ max|M̂| + a₁ max|K̂| (times the entries of a row,
/// bounded generously by 1e3 ε).
bool is_rayleigh(const ReducedSystem& r, const RayleighCoefficients& c) {
  const auto largest = [](const Eigen::SparseMatrix<double>& a) {
    return a.nonZeros() > 0 ? a.coeffs().cwiseAbs().maxCoeff() : 0.0;
  };
  const Eigen::SparseMatrix<double> gap = r.C - (c.a0 * r.M + c.a1 * r.K);
  const double scale = c.a0 * largest(r.M) + c.a1 * largest(r.K);
  return largest(gap) <= 1e3 * std::numeric_limits<double>::epsilon() * scale;
}

}  // namespace

ReducedOde::ReducedOde(const Model& model, const ReducedSystem& reduced)
    : model_(model), reduced_(reduced), nm_(static_cast<int>(reduced.M.rows())) {
  held_ = held_massless(reduced.M, model.has_damping() ? reduced.C : Eigen::SparseMatrix<double>(),
                        reduced.K, Eigen::SparseMatrix<double>(0, nm_));
  // With held DOFs, their consistency system stands in for M̂ (regular on the rest).
  if (!held_) {
    auto mass = std::make_shared<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(reduced.M);
    bool ok = mass->info() == Eigen::Success;
    if (ok && nm_ > 0) {
      const Eigen::VectorXd d = mass->vectorD();
      // Positive definite beyond roundoff of the largest pivot: the model's own check warns
      // from a spread of 1/eps (models/assembly/input_checks.cpp). 1e-14 of the largest refused a
      // sound mass of 1e-14 kg beside 2 kg, which every multiplier scheme integrates.
      ok = d.minCoeff() > std::numeric_limits<double>::epsilon() * d.cwiseAbs().maxCoeff();
    }
    if (!ok) {
      // The named slaves decide the reduction: one whose coefficient is small beside its row's
      // others (1e-11 u_b against u_a) made it singular to roundoff where the automatic choice
      // (the largest coefficients) runs.
      throw SchemeNotApplicable(
          std::string("the reduced mass matrix is singular to roundoff: elimination needs "
                      "inertia on every motion of the master DOFs that their stiffness does not "
                      "hold; the multiplier schemes (ggl, index1) integrate such a model") +
          (reduced.named_slaves
               ? ". The slaves are those of [solve] slaves: one whose coefficient is small "
                 "beside the others of its constraint makes the reduction ill-conditioned; "
                 "leave slaves out for the automatic choice"
               : ""));
    }
    mass_ = std::move(mass);
  }
  const bool damped = model.has_damping();
  const double entries = static_cast<double>(reduced.M.nonZeros() + reduced.K.nonZeros() +
                                             (damped ? reduced.C.nonZeros() : 0));
  if (entries >= kLanedProductFewestEntries) {
    if (damped && model.rayleigh && is_rayleigh(reduced, *model.rayleigh)) {
      rayleigh_ = model.rayleigh;
    }
    std::vector<const Eigen::SparseMatrix<double>*> matrices{&reduced.M, &reduced.K};
    if (damped && !rayleigh_) matrices.push_back(&reduced.C);
    products_ = std::make_shared<const SymmetricProducts>(matrices);
  }
  jacobian_ = BlockJacobian(size());
  jacobian_.declare_identity(0, 0, nm_);
  jacobian_.declare_identity(0, nm_, nm_);
  jacobian_.declare(nm_, 0, reduced.K);
  jacobian_.declare(nm_, nm_, reduced.C);
  jacobian_.declare(nm_, nm_, reduced.M);
  jacobian_.finish();
}

void ReducedOde::residual(double t, ConstRef y, ConstRef yp, Ref r) const {
  const auto x = y.head(nm_), w = y.tail(nm_);
  r.head(nm_) = yp.head(nm_) - w;
  if (products_) {
    // On the stack: the residual is IDA's most frequent call.
    std::array<ProductInput, 3> inputs{ProductInput{yp.tail(nm_).data()}, ProductInput{x.data()},
                                       ProductInput{w.data()}};
    std::size_t count = model_.has_damping() ? 3 : 2;
    if (rayleigh_) {
      inputs[0].v1 = inputs[1].v1 = w.data();
      inputs[0].c1 = rayleigh_->a0;
      inputs[1].c1 = rayleigh_->a1;
      count = 2;
    }
    products_->apply(std::span(inputs).first(count), r.tail(nm_).data());
    r.tail(nm_) -= reduced_.forces(model_, t, segment_start_.value_or(t));
    return;
  }
  r.tail(nm_) = reduced_.M * yp.tail(nm_) + reduced_.K * x -
                reduced_.forces(model_, t, segment_start_.value_or(t));
  if (model_.has_damping()) r.tail(nm_) += reduced_.C * w;
}

void ReducedOde::fill_jacobian(double /*t*/, ConstRef /*y*/, ConstRef /*yp*/, double cj,
                               JacobianMap J) const {
  std::fill_n(J.valuePtr(), J.nonZeros(), 0.0);
  BlockJacobian::add_identity(J, 0, 0, nm_, cj);
  BlockJacobian::add_identity(J, 0, nm_, nm_, -1.0);
  BlockJacobian::add(J, nm_, 0, reduced_.K);
  BlockJacobian::add(J, nm_, nm_, reduced_.C);
  BlockJacobian::add(J, nm_, nm_, reduced_.M, cj);
}

void ReducedOde::make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const {
  yp.resize(size());
  if (held_) {
    Eigen::VectorXd x = y.head(nm_), w = y.tail(nm_);
    const Eigen::VectorXd f = reduced_.forces(model_, t, t);
    const Eigen::VectorXd fdot =
        time_derivative(t, f, [&](double s) { return reduced_.forces(model_, s, t); });
    const Eigen::VectorXd a = held_->consistent(rhs_at(f, x, w), fdot, x, w);
    y << x, w;
    yp << w, a;
    return;
  }
  yp.head(nm_) = y.tail(nm_);
  yp.tail(nm_) = acceleration(t, y.head(nm_), y.tail(nm_));
}

Eigen::VectorXd ReducedOde::rhs_at(const Eigen::VectorXd& f, const Eigen::VectorXd& x,
                                   const Eigen::VectorXd& w) const {
  Eigen::VectorXd rhs = f - reduced_.K * x;
  if (model_.has_damping()) rhs -= reduced_.C * w;
  return rhs;
}

Eigen::VectorXd ReducedOde::acceleration(double t, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& w) const {
  const Eigen::VectorXd rhs = rhs_at(reduced_.forces(model_, t, t), x, w);
  if (!held_) return mass_->solve(rhs);
  Eigen::VectorXd xs = x, ws = w;  // consistent already: the changes are roundoff
  Eigen::VectorXd a = held_->consistent(rhs, Eigen::VectorXd::Zero(nm_), xs, ws);
  for (int h : held_->dofs()) a[h] = 0.0;
  return a;
}

std::unique_ptr<NewtonSystem> ReducedOde::newton_system() const {
  return std::make_unique<CondensedNewton>(
      Scheme::index1,
      LinearMatrices{reduced_.M, reduced_.C, reduced_.K, Eigen::SparseMatrix<double>(0, nm_)},
      Eigen::SparseMatrix<double>(0, 0));
}

}  // namespace condyn
