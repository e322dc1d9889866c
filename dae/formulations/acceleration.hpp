#pragma once
/// Accelerations at an output state, from the equations of motion (issue 13): the one mechanism
/// every scheme's rows go through (RowAssembler), so the output is consistent with the reported
/// reaction at the same row.

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <memory>
#include <optional>
#include <vector>

#include "dae/interface/held_massless.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/model.hpp"

namespace condyn {

/// u'' = M(t, u)⁻¹ (f(t, u, v) + f_con), f_con = −Aᵀλ the row's reaction: so
/// M u'' + C v + K u = f + f_con holds at the output state to the accuracy of the sparse LDLᵀ
/// solve (a few ulps times the condition of M), whatever the scheme. The result is as accurate
/// as (u, v, λ) themselves, the integrator's tolerances; no differencing.
/// Massless DOFs (zero row of M), whose momentum rows do not involve their acceleration:
/// - in a constraint: from the constraints at acceleration level, A u'' = γ(t, u, v), solved for
///   them given the others' (A's columns on them have full rank:
///   models/assembly/mass_regularity.cpp); by the rows on massless DOFs alone when those fix them
///   (exact: a support's 0, a drive's second derivative), else by all rows in the least-squares
///   sense;
/// - held by stiffness or damping (dae/interface/held_massless.hpp): from their momentum rows
///   differentiated, with the loads' exact time derivatives (a table's second derivative is 0
///   between its samples).
/// A constant mass matrix (linear model) is factored once, and so are the massless blocks.
class AccelerationFromForces {
 public:
  /// `held`: the model's massless DOFs held by stiffness (held_massless_of), or null.
  AccelerationFromForces(const Model& model, std::shared_ptr<const HeldMassless> held);
  [[nodiscard]] Eigen::VectorXd operator()(MechanicalSystem& system, double t,
                                           const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                           const Eigen::VectorXd& reaction);

 private:
  void factor(const Eigen::SparseMatrix<double>& mass);
  void constrained_massless(MechanicalSystem& system, double t, const Eigen::VectorXd& u,
                            const Eigen::VectorXd& v, Eigen::VectorXd& a);
  const Model& model_;
  bool constant_mass_;
  bool factored_ = false;
  Eigen::VectorXd massless_;  ///< 1 on the DOFs with a zero diagonal entry of M, else 0
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  std::shared_ptr<const HeldMassless> held_;  ///< held massless DOFs (linear models), or null
  std::vector<int> constrained_;              ///< the massless DOFs in a constraint
  bool normal_factored_ = false;              ///< A_Zᵀ A_Z factored (constant A)
  /// A_Z: the constrained massless DOFs' columns of the rows used (those on massless DOFs alone
  /// when they fix them, else all).
  Eigen::SparseMatrix<double> az_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> normal_;
};

}  // namespace condyn
