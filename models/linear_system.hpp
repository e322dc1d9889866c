#pragma once
/// A Model (constant M, C, K, linear constraints with constant coefficients) as a
/// MechanicalSystem: f = loads − K u − C u', A constant, φ = A_p u − g(t),
/// ψ = A u' − g'(t) (position rows) or A u' − h(t) (velocity rows), γ = g'' or h'.
/// Rows whose right-hand side is identically zero never evaluate a time function.

#include "models/linear_rows.hpp"
#include "models/mechanical_system.hpp"
#include "models/model.hpp"

namespace condyn {

class LinearSystem final : public MechanicalSystem {
 public:
  explicit LinearSystem(const Model& model);  ///< keeps a reference

  [[nodiscard]] int dofs() const override { return model_.dofs(); }
  [[nodiscard]] int constraints() const override { return model_.constraint_count(); }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return position_; }
  [[nodiscard]] const Sparse& mass(double /*t*/, ConstRef /*u*/) const override { return model_.M; }
  void force(double t, double step_reference, ConstRef u, ConstRef v, Ref f) const override;
  [[nodiscard]] const Sparse& force_jacobian_u(double /*t*/, ConstRef /*u*/,
                                               ConstRef /*v*/) const override {
    return minus_K_;
  }
  /// No nonzeros without damping: the block drops out of the pattern.
  [[nodiscard]] const Sparse& force_jacobian_v(double /*t*/, ConstRef /*u*/,
                                               ConstRef /*v*/) const override {
    return minus_C_;
  }
  [[nodiscard]] const Sparse& constraint_jacobian(double /*t*/, ConstRef /*u*/) const override {
    return model_.A;
  }
  void position_residual(double t, ConstRef u, Ref phi) const override {
    rows_.position_residual(t, u, phi);
  }
  void velocity_residual(double t, ConstRef /*u*/, ConstRef v, Ref psi) const override {
    rows_.velocity_residual(t, v, psi);
  }
  void acceleration_bias(double t, ConstRef /*u*/, ConstRef /*v*/, Ref gamma) const override {
    rows_.acceleration_bias(t, gamma);
  }
  /// ½u'ᵀMu' + ½uᵀKu − f·u when the model is conservative: no damping, constant loads (steps at
  /// t = 0 included) and scleronomic constraints.
  [[nodiscard]] std::optional<double> energy(double t, ConstRef u, ConstRef v) const override;

  /// Rows whose right-hand side is evaluated at all (the others are homogeneous and scleronomic).
  [[nodiscard]] int rows_with_time_functions() const { return rows_.rows_with_time_functions(); }

 private:
  const Model& model_;
  LinearRows rows_;
  std::vector<bool> position_;
  Sparse minus_K_, minus_C_;
  bool conservative_ = false;
};

}  // namespace condyn
