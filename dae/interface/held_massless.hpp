#pragma once
/// Massless DOFs held by stiffness (issue 13): a DOF with a zero row and column of M that no
/// constraint row touches has no inertia, yet its stiffness (or damping) row holds it,
///
///   C_h· u' + K_h· u = f_h(t)        (the momentum row h, M_h· = 0, (Aᵀλ)_h = 0),
///
/// an algebraic equation for u_h when the DOF has no damping (C_h· = 0, "undamped"), a first-order
/// one when it has (c_hh > 0, "damped"). The formulations keep their [u; v; ...] layout and
/// integrate these DOFs as the DAE they are:
/// - v_h never appears differentiated (M's column h is zero): it is algebraic (IDA id 0);
/// - undamped: u_h is fixed by its row at every step (index 1 in u) and v_h = u_h' is its BDF
///   derivative, of index 2 (it feeds no other row, as C's row and column h are zero): left out
///   of the local error test like the other index-2 unknowns (DaeProblem::variable_index);
/// - damped: u_h is differential (first order) and v_h an index-1 algebraic unknown.
/// Their consistent values at a segment start replace the KKT system [M Aᵀ; A 0][u''; λ] = [f; γ]
/// by the same system with M's column h replaced by K's (undamped: the unknown is the change of
/// u_h) or C's (damped: the change of v_h): u_h (undamped) and v_h (damped) are recomputed, not
/// kept. The derivatives follow from the momentum rows differentiated once:
/// K_HuHu v_Hu = ḟ_Hu − K_Hu,rest v_rest and C_HdHd u''_Hd = ḟ_Hd − C_Hd,rest u''_rest − K_Hd· v.
/// Linear systems only (constant M, C, K, A); models/assembly/mass_regularity.cpp refuses the
/// others.

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "dae/linsolve/kkt.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/massless_dofs.hpp"
#include "models/core/model.hpp"

namespace condyn {

class HeldMassless {
 public:
  /// Finds the held massless DOFs of the constant matrices (C may be 0 x 0: no damping). Throws
  /// std::invalid_argument when such a DOF has damping coupling (C_h· ≠ 0) but no damping of its
  /// own (c_hh = 0). `consistency` false skips factoring the KKT system consistent() needs (for
  /// accelerations() alone).
  explicit HeldMassless(LinearMatrices matrices, bool consistency = true);

  [[nodiscard]] bool empty() const { return held_.empty(); }
  /// The held massless DOFs, ascending.
  [[nodiscard]] const std::vector<int>& dofs() const { return held_; }
  /// Those without damping of their own (algebraic u), and those with it (first order in u).
  [[nodiscard]] const std::vector<int>& undamped() const { return undamped_; }
  [[nodiscard]] const std::vector<int>& damped() const { return damped_; }
  /// In a [u; v; ...] layout of n DOFs: v_h algebraic (id 0); index 2 on the undamped ones' v_h.
  void mark(Eigen::VectorXd& id, Eigen::VectorXd& index) const;

  /// Makes (u, v) consistent at a segment start and returns [u''; λ] (n + m): solves the KKT
  /// system with M's columns h replaced as above, rhs = [f(t, u, v); γ] as the scheme writes it,
  /// then the differentiated rows with fdot = ∂f/∂t at (t, u, v). u''_h of the undamped DOFs is
  /// 0 (v_h's derivative enters no equation). Throws std::runtime_error when a system is singular
  /// (a held DOF whose stiffness block is singular: a mechanism of massless DOFs).
  [[nodiscard]] Eigen::VectorXd consistent(const Eigen::VectorXd& rhs, const Eigen::VectorXd& fdot,
                                           Eigen::VectorXd& u, Eigen::VectorXd& v) const;

  /// Sets the held DOFs' displacements and velocities from their rows at an output state, given
  /// the other DOFs': u_Hu from K_Hu· u = f_Hu, v_Hd from C_Hd· v + K_Hd· u = f_Hd, then v_Hu from
  /// K_Hu· v = ḟ_Hu. The integrator holds the first two to its Newton tolerance and the last,
  /// an index-2 unknown outside its error test, only to the BDF derivative's accuracy (2.6e-8
  /// against 1e-10 on a chain at rtol 1e-10: tests/dae/test_held_massless.cpp).
  void settle(const Eigen::VectorXd& f, const Eigen::VectorXd& fdot, Eigen::VectorXd& u,
              Eigen::VectorXd& v) const;

  /// Sets the held DOFs' accelerations in `a`, given every other DOF's, from their momentum rows
  /// differentiated: damped, C_HdHd a_Hd = ḟ_Hd − C_Hd,rest a_rest − K_Hd· v (once); undamped,
  /// K_HuHu a_Hu = f̈_Hu − K_Hu,rest a_rest (twice; their C rows are zero). fdot, fddot: the
  /// applied loads' time derivatives.
  void accelerations(const Eigen::VectorXd& v, const Eigen::VectorXd& fdot,
                     const Eigen::VectorXd& fddot, Eigen::VectorXd& a) const;

 private:
  LinearMatrices l_;
  std::vector<int> held_, undamped_, damped_;
  std::shared_ptr<KktLu> kkt_, stiff_, damp_;
};

/// differential_id and variable_index of a [u; v] problem of `size` unknowns, all differential
/// and of index 1 but for the held DOFs (`held` null: none; the index is then empty, the
/// DaeProblem default).
[[nodiscard]] Eigen::VectorXd held_differential_id(const HeldMassless* held, Eigen::Index size);
[[nodiscard]] Eigen::VectorXd held_variable_index(const HeldMassless* held, Eigen::Index size);

/// The held massless DOFs of constant matrices (C may be 0 x 0), or null when there are none.
/// Which DOFs are massless and unconstrained is read from M and A as given; the matrices are
/// copied only when there are some (at a million DOFs a copy of K is tens of megabytes).
[[nodiscard]] std::shared_ptr<const HeldMassless> held_massless(
    const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& C,
    const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& A,
    bool consistency = true);
/// The same for a linear system's matrices, read from it without copying them.
[[nodiscard]] std::shared_ptr<const HeldMassless> held_massless_of(const MechanicalSystem& system);
/// The held massless DOFs of a model, or null: none, or a nonlinear model (refused there).
[[nodiscard]] std::shared_ptr<const HeldMassless> held_massless_of(const Model& model);

/// Forward difference of a force function of time at fixed state, ∂f/∂t ≈ (f(t + δ) − f(t))/δ
/// with δ = 1e-7 max(1, |t|): the right-hand derivative a segment starting at t sees (table
/// functions have kinks at their samples). Only the seed of the held DOFs' histories depends on
/// it, not the solution (their rows are solved at every step).
template <class Force>
[[nodiscard]] Eigen::VectorXd time_derivative(double t, const Eigen::VectorXd& f0, Force&& force) {
  const double delta = 1e-7 * std::max(1.0, std::abs(t));
  return (force(t + delta) - f0) / delta;
}

}  // namespace condyn
