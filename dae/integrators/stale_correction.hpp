#pragma once
/// Newton corrections from a stale matrix that keep the algebraic equations exact.
///
/// IDA factors J₀ = ∂F/∂y + cj₀ ∂F/∂y' and keeps it while cj moves (up to a factor 1.67). A
/// correction δ = −J₀⁻¹F is then scaled by s = 2/(1 + cj/cj₀), which approximates the current
/// matrix's inverse on the differential equations. An equation without y' (GGL's ψ = 0 and φ = 0,
/// index2's and index3's constraint rows) has the same row in J₀ as at any cj, so δ satisfies its
/// linearization exactly and the scaled sδ leaves (1 − s) of its residual; the multipliers and the
/// constraint rows then converge only geometrically, costing Newton iterations at every step
/// (docs/benchmarks.md has the benchmark lattice's).
///
/// Here the differential part x of δ is split along the rows W = J₀[algebraic equations,
/// differential unknowns]: the component P x, P = Wᵀ(WWᵀ)⁻¹W, is what those equations see and
/// stays; the rest is scaled by s; the algebraic unknowns (multipliers) stay unscaled, since the
/// algebraic equations do not depend on them here. So x ← s x + (1 − s) P x, and W x is as J₀
/// solved it. When WWᵀ is singular or nearly so (redundant or nearly redundant rows, pivot below
/// 1e-12 of the largest with W's rows scaled to unit length) the whole correction is scaled by s,
/// as IDA does. Only GGL declares algebraic equations (MultiplierDae::algebraic_equations:
/// index2's and index3's nonlinear scenes lost with it, docs/schemes.md); the Ida integrator
/// turns IDA's scaling off where this applies. SUNDIALS types stay inside dae/.

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <functional>
#include <utility>
#include <vector>

#include "models/core/eigen_decompositions.hpp"

namespace condyn {

class StaleCorrection {
 public:
  /// `algebraic_equations[i]`: equation i has no y'; `differential_id`: 1 for a differential
  /// unknown, 0 for an algebraic one (DaeProblem::differential_id).
  StaleCorrection(const std::vector<bool>& algebraic_equations,
                  const Eigen::VectorXd& differential_id);

  /// The Newton matrix J₀ was formed at cj₀: W, its factorization and cj₀ are taken from it.
  template <class Sparse>
  void update(const Sparse& J, double cj0);

  /// x (a correction J₀⁻¹b) for the current cj: as above, or x·s when W is unusable.
  void apply(double cj, Eigen::Ref<Eigen::VectorXd> x) const;

  /// Whether the last update found WWᵀ well conditioned (tests).
  [[nodiscard]] bool projects() const { return projects_; }

 private:
  void factor();

  std::vector<int> equation_row_;  ///< equation -> row of W, or −1
  /// The differential unknowns as runs [first, last) (one run for MultiplierDae's [u; v]).
  std::vector<std::pair<int, int>> differential_runs_;
  /// W's columns: the differential unknowns with an entry in an algebraic equation, ascending.
  /// W has only these columns, so a correction costs one scaling pass plus O(nnz W): nothing
  /// the size of the state is gathered or formed (10⁶ DOFs under GGL: W has some 10⁵ entries).
  std::vector<int> columns_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> w_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  std::vector<Eigen::Triplet<double>> triplets_;
  double cj0_ = 0.0;
  bool projects_ = false;
  mutable Eigen::VectorXd touched_, rows_;
};

template <class Sparse>
void StaleCorrection::update(const Sparse& J, double cj0) {
  static_assert(!Sparse::IsRowMajor, "update walks the Newton matrix by columns");
  cj0_ = cj0;
  triplets_.clear();
  columns_.clear();
  for (const auto& [first, last] : differential_runs_) {
    for (int k = first; k < last; ++k) {
      bool touched = false;
      for (typename Sparse::InnerIterator it(J, k); it; ++it) {
        const int row = equation_row_[static_cast<std::size_t>(it.row())];
        if (row < 0 || it.value() == 0.0) continue;
        if (!touched) columns_.push_back(k);
        touched = true;
        triplets_.emplace_back(row, static_cast<int>(columns_.size()) - 1, it.value());
      }
    }
  }
  factor();
}

namespace sundials {

/// `inner` (which it owns and frees) with each solution corrected by `correction` for the cj
/// `current` gives (IDAGetCurrentCj). IDA's own scaling must be off
/// (IDASetLinearSolutionScaling). Returns nullptr when out of memory (then `inner` is freed).
[[nodiscard]] SUNLinearSolver make_stale_corrected_solver(SUNLinearSolver inner,
                                                          const StaleCorrection& correction,
                                                          std::function<bool(double&)> current,
                                                          SUNContext ctx);

}  // namespace sundials

}  // namespace condyn
