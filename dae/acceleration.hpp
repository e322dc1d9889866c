#pragma once
/// Accelerations at an output state, from the equations of motion (issue 13): the one mechanism
/// every scheme's rows go through (RowAssembler), so the output is consistent with the reported
/// reaction at the same row.

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <optional>

#include "models/mechanical_system.hpp"

namespace condyn {

/// u'' = M(t, u)⁻¹ (f(t, u, v) + f_con), f_con = −Aᵀλ the row's reaction: so
/// M u'' + C v + K u = f + f_con holds at the output state to the accuracy of the sparse LDLᵀ
/// solve (a few ulps times the condition of M), whatever the scheme. The result is as accurate
/// as (u, v, λ) themselves, the integrator's tolerances; no differencing. A massless DOF (zero row
/// of M, an algebraic DOF) gets NaN: its acceleration is not defined by these equations.
/// A constant mass matrix (linear model) is factored once.
class AccelerationFromForces {
 public:
  explicit AccelerationFromForces(bool constant_mass) : constant_mass_(constant_mass) {}
  [[nodiscard]] Eigen::VectorXd operator()(MechanicalSystem& system, double t,
                                           const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                           const Eigen::VectorXd& reaction);

 private:
  void factor(const Eigen::SparseMatrix<double>& mass);
  bool constant_mass_;
  bool factored_ = false;
  Eigen::VectorXd massless_;  ///< 1 on the DOFs with a zero diagonal entry of M, else 0
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

}  // namespace condyn
