#pragma once
/// The chapter's elimination path (§5.5, §5.6). Every constraint is linear with constant
/// coefficients and integrable, so all of them are written at position level, A u = g(t), and
/// eliminated by the master-slave transformation u = T û + G g(t)
/// (models/core/master_slave.hpp), of which direct elimination of single-freedom constraints
/// is the special case where every slave is the DOF its constraint names (T selects the remaining
/// DOFs, G injects g). The reduced system
///
///   M̂ û'' + Ĉ û' + K̂ û = f̂(t),  M̂ = TᵀMT, Ĉ = TᵀCT, K̂ = TᵀKT,
///   f̂(t) = Tᵀ f(t) + Tᵀ f_tra(t),  f_tra = −K G g − C G g' − M G g''  (eqs. 5.10, 5.26 corrected)
///
/// is integrated with IDA as an ODE (dae/formulations/reduced_ode.hpp, run by
/// dae/formulations/elimination_run.cpp); full displacements and velocities are reconstructed, and
/// the reactions come from the full equations: f_con = M u'' + C u' + K u − f (eqs. 5.8, 5.12).

#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

#include "models/core/master_slave.hpp"
#include "models/core/model.hpp"

namespace condyn {

/// The reduced linear system of the elimination path, with everything the chapter prints.
struct ReducedSystem {
  MasterSlave transform;
  Eigen::SparseMatrix<double> M, C, K;  ///< M̂, Ĉ, K̂ (C empty without damping)
  /// Reduced transfer-force coefficients: f̂_tra(t) = FK g + FC g' + FM g'' (nm x m each, sparse:
  /// nonzero only near the slaves): FK = −TᵀKG, FC = −TᵀCG, FM = −TᵀMG.
  Eigen::SparseMatrix<double> FK, FC, FM;
  /// nm x (number of loads): Tᵀ b_k, b_k = e_dof(k) or the load's pattern (sparse columns).
  Eigen::SparseMatrix<double> loads;
  bool rheonomic = false;     ///< some constraint right-hand side is nonzero: transfer forces exist
  bool named_slaves = false;  ///< the slaves are [solve] slaves, not the automatic choice

  /// f̂(t) for the current segment (steps on when start <= step_reference).
  [[nodiscard]] Eigen::VectorXd forces(const Model& model, double t, double step_reference) const;
};

/// `preferred_slaves` ([solve] slaves: DOF names, size m, or empty) as master_slave_transform.
/// Its CoupledGroupTooLarge is rethrown as SchemeNotApplicable
/// (dae/interface/scheme_not_applicable.hpp) naming the group's first constraint.
[[nodiscard]] ReducedSystem reduce(const Model& model,
                                   const std::vector<std::string>& preferred_slaves = {});

}  // namespace condyn
