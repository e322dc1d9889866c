#pragma once
/// How far the constraint rows at a configuration are from losing rank: the measure by which a
/// run's passages near singular configurations are found (dae/run/singular_passages.hpp) and by
/// which the BDF schemes bridge them (dae/integrators/passage_bridge.hpp).

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <memory>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

/// The conditioning of the constraint rows at a configuration: σ_min of Â = N A W, W = M_d^(-1/2)
/// (M_d: M's diagonal; a massless column weighs as the lightest massive one) and N scaling each
/// row of A W to unit length. 1 for orthogonal rows, 0 where they are dependent; it does not
/// depend on the rows' or the masses' units. Estimated by inverse iteration on Â Âᵀ (a dense
/// Cholesky up to 64 rows, a sparse LDLᵀ above, its pattern analysed once; warm started from the
/// last call), which converges in one or two solves where it matters, near a singular
/// configuration.
class ConstraintConditioning {
 public:
  explicit ConstraintConditioning(const MechanicalSystem& system);
  /// σ_min at (t, u) (0 when Â Âᵀ is singular to its factorization). A call at the last call's
  /// exact (t, u) returns its value without computing it again: a run's monitor and its bridge
  /// (dae/integrators/passage_bridge.hpp) ask at every step's state.
  double operator()(double t, const Eigen::VectorXd& u);
  /// After operator(): the share of the kinetic energy of velocity v in the directions the rows
  /// at that configuration forbid, ‖P p‖² / ‖p‖² with p = W⁻¹ v and P the projection on the row
  /// space of Â; −1 when v carries no kinetic energy or the rows were singular.
  [[nodiscard]] double forbidden_share(const Eigen::VectorXd& v) const;

 private:
  /// Up to this many rows the Gram matrix is dense (m² doubles, 32 KB at 64).
  static constexpr Eigen::Index kDenseRows = 64;
  /// operator() without the reuse.
  double sigma_min(double t, const Eigen::VectorXd& u);
  void weigh(double t, const Eigen::VectorXd& u);
  bool factor_gram();
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& x) const;

  std::unique_ptr<MechanicalSystem> system_;
  const Eigen::SparseMatrix<double>* rows_ = nullptr;  ///< A at the last call (system_'s)
  Eigen::VectorXd weight_;                             ///< W's diagonal at the last call
  Eigen::VectorXd norms_;                              ///< N's diagonal at the last call
  Eigen::MatrixXd dense_gram_;
  Eigen::LLT<Eigen::MatrixXd> dense_;
  Eigen::SparseMatrix<double> scaled_, sparse_gram_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> sparse_;
  bool analysed_ = false, factored_ = false;
  Eigen::Index gram_nonzeros_ = 0;
  Eigen::VectorXd start_;  ///< the last left singular vector estimate
  double last_t_ = 0.0;    ///< the last call's time, state and value
  Eigen::VectorXd last_u_;
  double last_sigma_ = 0.0;
};

}  // namespace condyn
