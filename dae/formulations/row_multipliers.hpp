#pragma once
/// λ at an output row from the constraints at acceleration level, the same quantity under every
/// multiplier scheme: [M Aᵀ; A 0] [u''; λ] = [f(t, u, u'); γ(t, u, u')] at the row's own state.
///
/// The schemes' own λ means different things: index-1's is this one (at its steps), Baumgarte's
/// carries the stabilization terms, GGL's and index-2's are velocity-level unknowns, and index-3's
/// is an index-3 unknown that BDF's error test does not control (on a stiff chain it was off by
/// 2.7 where the exact reaction peaks at 0.24, docs/limitations.md). Between steps the
/// interpolated λ also misses a load table's kinks. Solving the saddle-point system at the row
/// gives the reaction that holds the row's u and u' on the constraints under the exact loads, as
/// the projection scheme and the elimination path report theirs.

#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Sparse>

#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

class AccelerationLevelMultipliers {
 public:
  /// `constant`: M and A do not depend on (t, u) (a linear system), so the matrix is factored
  /// once; otherwise it is refactored at every row (same pattern, KLU's pivots reused).
  AccelerationLevelMultipliers(const MechanicalSystem& system, bool constant);

  /// u'' and λ at (t, u, u'); nothing when the saddle-point matrix is singular or its solution
  /// does not satisfy both blocks to 1e-8 relative (a massless DOF in rows that do not fix its
  /// acceleration), in which case the caller keeps the scheme's λ. Massless DOFs in no row are
  /// decoupled: their u'' reads 0 here and is not meant to be used.
  [[nodiscard]] std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> operator()(
      double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v);

 private:
  bool factor(double t, const Eigen::VectorXd& u);

  std::unique_ptr<MechanicalSystem> system_;
  bool constant_;
  bool usable_ = true;
  bool factored_ = false;
  std::vector<int> decoupled_;          ///< massless DOFs in no row: a unit on their diagonal
  Eigen::VectorXd scale_;               ///< D: a power of two per row of A, near 1/max|a_ij|
  Eigen::SparseMatrix<double> scaled_;  ///< D A
  FixedPatternKlu klu_;
};

}  // namespace condyn
