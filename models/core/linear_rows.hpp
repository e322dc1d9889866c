#pragma once
/// Constraint rows that are linear with constant coefficients (the chapter's kind), evaluated
/// for any MechanicalSystem that contains them:
///
///   position rows:  φ = a·u − g(t),   ψ = a·u' − g'(t),   γ = g''(t)
///   velocity rows:  φ = 0,            ψ = a·u' − h(t),    γ = h'(t)
///
/// Rows whose right-hand side is identically zero never evaluate a time function.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

#include "models/core/model.hpp"

namespace condyn {

class LinearRows {
 public:
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  using Ref = Eigen::Ref<Eigen::VectorXd>;

  LinearRows() = default;
  explicit LinearRows(std::vector<Constraint> rows);

  [[nodiscard]] int size() const { return static_cast<int>(rows_.size()); }
  [[nodiscard]] bool is_position(int i) const { return position_[static_cast<std::size_t>(i)]; }
  /// Rows whose right-hand side is evaluated at all.
  [[nodiscard]] int rows_with_time_functions() const;
  /// The first size() entries of phi, psi and gamma.
  void position_residual(double t, const ConstRef& u, Ref phi) const;
  void velocity_residual(double t, const ConstRef& v, Ref psi) const;
  void acceleration_bias(double t, Ref gamma) const;
  /// Appends the coefficients as triplets, row i at row0 + i.
  void append_triplets(int row0, std::vector<Eigen::Triplet<double>>& out) const;

 private:
  /// d^order/dt^order of row i's right-hand side at its own level (g or h); 0 without
  /// evaluation for homogeneous scleronomic rows.
  [[nodiscard]] double rhs(std::size_t i, int order, double t) const;

  std::vector<Constraint> rows_;
  std::vector<bool> position_, has_rhs_;
};

}  // namespace condyn
