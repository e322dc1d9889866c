// Newton corrections from a stale matrix that keep the algebraic equations exact
// (dae/integrators/stale_correction.hpp).

#include "dae/integrators/stale_correction.hpp"

#include <nvector/nvector_serial.h>

#include <cmath>
#include <exception>
#include <new>
#include <utility>

#include "dae/integrators/linear_solver_parts.hpp"

namespace condyn {

namespace {

/// A pivot of WWᵀ (rows of unit length, so its diagonal is 1) below this fraction of the largest
/// marks the rows as (nearly) dependent.
constexpr double kMinPivot = 1e-12;

}  // namespace

StaleCorrection::StaleCorrection(const std::vector<bool>& algebraic_equations,
                                 const Eigen::VectorXd& differential_id)
    : equation_row_(algebraic_equations.size(), -1) {
  int rows = 0;
  for (std::size_t i = 0; i < algebraic_equations.size(); ++i) {
    if (algebraic_equations[i]) equation_row_[i] = rows++;
  }
  const auto n = static_cast<int>(differential_id.size());
  for (int j = 0; j < n;) {
    if (differential_id[j] == 0.0) {
      ++j;
      continue;
    }
    const int first = j;
    while (j < n && differential_id[j] != 0.0) ++j;
    differential_runs_.emplace_back(first, j);
  }
  w_.resize(rows, 0);
}

void StaleCorrection::factor() {
  projects_ = false;
  w_.resize(w_.rows(), static_cast<Eigen::Index>(columns_.size()));
  w_.setFromTriplets(triplets_.begin(), triplets_.end());
  // Rows of unit length; a row without differential unknowns makes WWᵀ singular.
  for (Eigen::Index i = 0; i < w_.outerSize(); ++i) {
    const double norm = w_.row(i).norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) return;
    w_.row(i) /= norm;
  }
  const Eigen::SparseMatrix<double> wwt = w_ * w_.transpose();
  ldlt_.compute(wwt);
  if (ldlt_.info() != Eigen::Success) return;
  const Eigen::VectorXd d = ldlt_.vectorD();
  projects_ = d.size() > 0 && d.minCoeff() > kMinPivot * d.maxCoeff();
}

void StaleCorrection::apply(double cj, Eigen::Ref<Eigen::VectorXd> x) const {
  // No matrix yet (IDA sets one up before its first solve) or the same cj: as solved.
  if (!(cj0_ > 0.0) || cj == cj0_) return;
  const double s = 2.0 / (1.0 + cj / cj0_);
  if (!projects_) {
    x *= s;
    return;
  }
  // x_d ← s x_d + (1 − s) Wᵀ(WWᵀ)⁻¹W x_d; the algebraic unknowns stay. W x_d and Wᵀ(…) live on
  // W's columns only, so those are gathered before x_d is scaled in place and added after.
  touched_.resize(static_cast<Eigen::Index>(columns_.size()));
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    touched_[static_cast<Eigen::Index>(k)] = x[columns_[k]];
  }
  rows_ = w_ * touched_;
  rows_ = ldlt_.solve(rows_);
  touched_.noalias() = (1.0 - s) * (w_.transpose() * rows_);
  for (const auto& [first, last] : differential_runs_) x.segment(first, last - first) *= s;
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    x[columns_[k]] += touched_[static_cast<Eigen::Index>(k)];
  }
}

namespace sundials {

namespace {

struct CorrectedContent {
  SUNLinearSolver inner;
  const StaleCorrection* correction;
  std::function<bool(double&)> current;
  int last_flag;
};

CorrectedContent& corrected(SUNLinearSolver s) { return content_of<CorrectedContent>(s); }

SUNLinearSolver_Type corrected_type(SUNLinearSolver s) {
  return SUNLinSolGetType(corrected(s).inner);
}

int corrected_initialize(SUNLinearSolver s) {
  return corrected(s).last_flag = SUNLinSolInitialize(corrected(s).inner);
}

int corrected_setup(SUNLinearSolver s, SUNMatrix a) {
  return corrected(s).last_flag = SUNLinSolSetup(corrected(s).inner, a);
}

int corrected_solve(SUNLinearSolver s, SUNMatrix a, N_Vector x, N_Vector b, double tol) {
  CorrectedContent& c = corrected(s);
  c.last_flag = SUNLinSolSolve(c.inner, a, x, b, tol);
  if (c.last_flag != SUNLS_SUCCESS) return c.last_flag;
  double cj = 0.0;
  if (!c.current(cj)) return c.last_flag = SUNLS_MEM_NULL;
  try {
    c.correction->apply(cj, view(x));
  } catch (const std::bad_alloc&) {
    return c.last_flag = SUNLS_MEM_FAIL;
  }
  return c.last_flag;
}

int corrected_free(SUNLinearSolver s) {
  if (s == nullptr) return SUNLS_SUCCESS;
  if (s->content != nullptr) SUNLinSolFree(corrected(s).inner);
  return free_solver_of<CorrectedContent>(s);
}

}  // namespace

SUNLinearSolver make_stale_corrected_solver(SUNLinearSolver inner,
                                            const StaleCorrection& correction,
                                            std::function<bool(double&)> current, SUNContext ctx) {
  SUNLinearSolver s =
      new_solver_with<CorrectedContent>(ctx, inner, &correction, std::move(current), 0);
  if (s == nullptr) {
    SUNLinSolFree(inner);
    return nullptr;
  }
  s->ops->gettype = corrected_type;
  s->ops->initialize = corrected_initialize;
  s->ops->setup = corrected_setup;
  s->ops->solve = corrected_solve;
  s->ops->free = corrected_free;
  return s;
}

}  // namespace sundials

}  // namespace condyn
