#pragma once
/// The chapter's elimination path (§5.5, §5.6). Every constraint is linear with constant
/// coefficients and integrable, so all of them are written at position level, A u = g(t), and
/// eliminated by the master-slave transformation
///
///   u = T û + G g(t),   T (n x nm), G (n x m):  A T = 0, A G = I,
///
/// of which direct elimination of single-freedom constraints is the special case where every slave
/// is the DOF its constraint names (T selects the remaining DOFs, G injects g). The reduced system
///
///   M̂ û'' + Ĉ û' + K̂ û = f̂(t),  M̂ = TᵀMT, Ĉ = TᵀCT, K̂ = TᵀKT,
///   f̂(t) = Tᵀ f(t) + Tᵀ f_tra(t),  f_tra = −K G g − C G g' − M G g''  (eqs. 5.10, 5.26 corrected)
///
/// is integrated with IDA as an ODE; full displacements and velocities are reconstructed, and the
/// reactions come from the full equations: f_con = M u'' + C u' + K u − f (eqs. 5.8, 5.12).

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

#include "dae/solve_result.hpp"
#include "models/model.hpp"

namespace condyn {

/// u = T û + G g. Slaves are chosen by column pivoting on A (the best-conditioned set of m
/// columns) unless the caller names them.
struct MasterSlave {
  std::vector<int> masters, slaves;  ///< DOF indices, ascending
  Eigen::SparseMatrix<double> T;     ///< n x nm
  Eigen::SparseMatrix<double> G;     ///< n x m
};

/// Builds the transformation. `preferred_slaves` (DOF indices, size m) overrides the pivoting
/// choice. Throws std::invalid_argument when A is rank deficient or the named slaves do not form
/// an invertible block (naming them and the condition number).
[[nodiscard]] MasterSlave master_slave_transform(const Eigen::SparseMatrix<double>& A,
                                                 const std::vector<int>& preferred_slaves = {});

/// The reduced linear system of the elimination path, with everything the chapter prints.
struct ReducedSystem {
  MasterSlave transform;
  Eigen::SparseMatrix<double> M, C, K;  ///< M̂, Ĉ, K̂ (C empty without damping)
  /// Reduced transfer-force coefficients: f̂_tra(t) = FK g + FC g' + FM g'' (nm x m each):
  /// FK = −TᵀKG, FC = −TᵀCG, FM = −TᵀMG.
  Eigen::MatrixXd FK, FC, FM;
  Eigen::MatrixXd loads;   ///< nm x (number of loads): Tᵀ e_dof(k)
  bool rheonomic = false;  ///< some constraint right-hand side is nonzero: transfer forces exist

  /// f̂(t) for the current segment (steps on when start <= step_reference).
  [[nodiscard]] Eigen::VectorXd forces(const Model& model, double t, double step_reference) const;
};

/// `preferred_slaves` ([solve] slaves: DOF names, size m, or empty) as master_slave_transform.
[[nodiscard]] ReducedSystem reduce(const Model& model,
                                   const std::vector<std::string>& preferred_slaves = {});

/// Runs the elimination path with IDA into `result` (dae/observed_run.hpp), slaves as reduce().
/// Throws std::invalid_argument when the reduced mass matrix is singular (massless master DOFs are
/// not supported on this path).
void solve_elimination(const Model& model, const std::vector<std::string>& preferred_slaves,
                       const IntegratorOptions& options, SolveResult& result);

}  // namespace condyn
