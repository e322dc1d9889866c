#pragma once
/// The lowest eigenpairs of a symmetric pencil, K φ = ω² M φ (K symmetric positive semi-definite,
/// M symmetric positive semi-definite): the natural modes of a model whose constraints are already
/// eliminated (dae/formulations/natural_modes.hpp).
///
/// DOFs with no mass (a zero column of M) have no inertia: their rows K_H· φ = 0 are static, and
/// they are condensed out exactly (Guyan), K_c = K_RR − K_RH K_HH⁻¹ K_HR on the DOFs R with mass,
/// without forming K_c: a solve with K − σM and a zero right-hand side on H is a solve with
/// K_c − σM_RR. The pencil has |R| modes; φ_H = −K_HH⁻¹ K_HR φ_R.
///
/// Two paths, the same result: dense (Eigen's generalized self-adjoint solver on K_c, M_RR) for
/// small pencils, and shift-invert Lanczos (Spectra's SymGEigsShiftSolver) with a sparse LDLᵀ of
/// K − σM for large ones, σ slightly below zero so that the modes nearest it are the lowest.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <stdexcept>
#include <string>
#include <vector>

namespace condyn {

/// The pencil has no modes of the kind asked (no mass, massless DOFs nothing holds, a stiffness
/// that is not positive semi-definite, Lanczos not converging): the message says which.
class ModesUnavailable : public std::runtime_error {
 public:
  /// What is missing: the input at fault follows (the masses, the model, the influence vector).
  enum class Why { no_mass, nonlinear, stiffness, no_participation, not_converged };
  ModesUnavailable(Why reason, const std::string& what) : std::runtime_error(what), why(reason) {}
  Why why;
};

enum class ModeSolver { automatic, dense, sparse };

struct PencilModes {
  Eigen::VectorXd omega2;  ///< ω², ascending (count)
  Eigen::MatrixXd shapes;  ///< n x count, φᵀ M φ = 1, the entry of largest magnitude positive
  bool dense = false;      ///< which path computed them
};

/// The DOFs with a zero column of M (explicit zeros count as zero), ascending.
[[nodiscard]] std::vector<int> massless_columns(const Eigen::SparseMatrix<double>& M);

/// How many modes the pencil has: the DOFs with mass.
[[nodiscard]] int mode_count(const Eigen::SparseMatrix<double>& M);

/// `count` lowest modes (1 <= count <= mode_count(M), else std::invalid_argument). `automatic`
/// takes the dense path up to kDenseModeDofs DOFs, or when Lanczos cannot give `count` modes
/// (count >= |R| − 1) and the dense pencil fits kMaxDenseModeEntries; else Lanczos. Throws
/// ModesUnavailable as above.
[[nodiscard]] PencilModes lowest_modes(const Eigen::SparseMatrix<double>& K,
                                       const Eigen::SparseMatrix<double>& M, int count,
                                       ModeSolver solver = ModeSolver::automatic);

/// Lᵀ M_RR⁻¹ L over the DOFs R with mass (L zero on the massless ones): for L = M r, the mass
/// that moves along r, the sum over every mode of (φᵀ L)² with φᵀMφ = 1.
[[nodiscard]] double mass_along(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& L);

/// Up to this many DOFs the dense path is the default: its cost (n³) is then below a sparse
/// factorization's set-up, and it gives every mode.
inline constexpr int kDenseModeDofs = 400;
/// The dense path's limit (n² entries, 32 MB), as the dense modal damping's.
inline constexpr double kMaxDenseModeEntries = 4e6;
/// Relative residual of the Ritz pairs Lanczos is asked for (Spectra's tolerance on
/// |ν| of the shift-inverted pencil): eigenvalues to about this relative accuracy.
inline constexpr double kModeTolerance = 1e-10;

}  // namespace condyn
