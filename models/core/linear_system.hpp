#pragma once
/// A linear model (constant M, C, K, linear constraints with constant coefficients) as a
/// MechanicalSystem: f = loads − K u − C u', A constant, φ = A_p u − g(t),
/// ψ = A u' − g'(t) (position rows) or A u' − h(t) (velocity rows), γ = g'' or h'.
/// Rows whose right-hand side is identically zero never evaluate a time function.
///
/// It owns what it evaluates (copied from the model once, at build time; K shared with the
/// model, not copied) in one constant block that its clones share: a clone for a run costs a
/// pointer, not a copy of the matrices.

#include <memory>

#include "models/core/linear_rows.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/model.hpp"

namespace condyn {

class LinearSystem final : public MechanicalSystem {
 public:
  explicit LinearSystem(const Model& model);

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<LinearSystem>(*this);
  }
  [[nodiscard]] int dofs() const override { return static_cast<int>(data_->M.rows()); }
  [[nodiscard]] int constraints() const override { return data_->rows.size(); }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return data_->position; }
  [[nodiscard]] const Sparse& mass(double /*t*/, ConstRef /*u*/) override { return data_->M; }
  void force(double t, ConstRef u, ConstRef v, Ref f) override;
  [[nodiscard]] const Sparse& stiffness(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    return *data_->K;
  }
  /// No nonzeros without damping: the block drops out of the pattern.
  [[nodiscard]] const Sparse& damping(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    return data_->C;
  }
  [[nodiscard]] const Sparse& constraint_jacobian(double /*t*/, ConstRef /*u*/) override {
    return data_->A;
  }
  void position_residual(double t, ConstRef u, Ref phi) override {
    data_->rows.position_residual(t, u, phi);
  }
  void velocity_residual(double t, ConstRef /*u*/, ConstRef v, Ref psi) override {
    data_->rows.velocity_residual(t, v, psi);
  }
  void acceleration_bias(double t, ConstRef /*u*/, ConstRef /*v*/, Ref gamma) override {
    data_->rows.acceleration_bias(t, gamma);
  }
  /// ½u'ᵀMu' + ½uᵀKu − f·u when the model is conservative: no damping, constant loads (steps at
  /// t = 0 included) and scleronomic constraints.
  [[nodiscard]] std::optional<double> energy(double t, ConstRef u, ConstRef v) override;
  /// Strain energy ½uᵀKu, damping power vᵀC v, load power f(t)ᵀv: for every linear model.
  [[nodiscard]] std::optional<EnergyParts> energy_parts(double t, ConstRef u, ConstRef v) override;

  /// Rows whose right-hand side is evaluated at all (the others are homogeneous and scleronomic).
  [[nodiscard]] int rows_with_time_functions() const {
    return data_->rows.rows_with_time_functions();
  }

 private:
  struct Data {
    std::shared_ptr<const Sparse> K;  ///< the Model's own (Model::K): shared, not copied
    Sparse M, C, A;
    std::vector<Load> loads;
    LinearRows rows;
    std::vector<bool> position;
    bool damped = false, conservative = false;
  };
  std::shared_ptr<const Data> data_;
};

}  // namespace condyn
