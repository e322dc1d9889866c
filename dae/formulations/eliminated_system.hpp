#pragma once
/// The mixed formulation's system: a MechanicalSystem with some of its constant linear rows
/// eliminated (dae/formulations/constraint_treatment.hpp) by u = T q + G g_e(t), the rest kept for
/// the multiplier schemes. In the reduced coordinates q (the masters):
///
///   M̂(t, q) = Tᵀ M(t, u) T,   f̂ = Tᵀ (f(t, u, u') − M(t, u) G g_e''(t)),
///   kept rows: φ̂ = φ_k(t, u), ψ̂ = ψ_k(t, u, u'), Â = A_k(t, u) T, γ̂ = γ_k − A_k G g_e'',
///
/// with u = T q + G g_e(t), u' = T q' + G g_e'(t); every Jacobian block is the full one's,
/// mapped by T (columns) and Tᵀ or the kept-row selection (rows), so its pattern stays fixed.
/// The multipliers of the eliminated rows come from the full equations at an output,
/// A_eᵀ λ_e = f − M u'' − A_kᵀ λ_k (least squares with the constant A_e), so reactions mean
/// what they mean under every other scheme.

#include <Eigen/SparseCholesky>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "dae/formulations/constraint_treatment.hpp"
#include "dae/linsolve/fixed_product.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/model.hpp"
#include "models/core/time_function.hpp"

namespace condyn {

class EliminatedSystem final : public MechanicalSystem {
 public:
  /// `treatment` from treat_constraints(model). When the model is linear (constant M, C, K, A),
  /// the reduced matrices are formed once here and shared by the clones.
  EliminatedSystem(const Model& model, const ConstraintTreatment& treatment);
  EliminatedSystem(const EliminatedSystem& other);
  EliminatedSystem& operator=(const EliminatedSystem&) = delete;
  ~EliminatedSystem() override = default;

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<EliminatedSystem>(*this);
  }
  [[nodiscard]] int dofs() const override { return static_cast<int>(data_->T.cols()); }
  [[nodiscard]] int constraints() const override { return static_cast<int>(data_->kept.size()); }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return data_->position; }
  [[nodiscard]] const Sparse& mass(double t, ConstRef q) override;
  void force(double t, ConstRef q, ConstRef w, Ref f) override;
  [[nodiscard]] const Sparse& stiffness(double t, ConstRef q, ConstRef w) override;
  [[nodiscard]] const Sparse& damping(double t, ConstRef q, ConstRef w) override;
  [[nodiscard]] const Sparse& constraint_jacobian(double t, ConstRef q) override;
  void position_residual(double t, ConstRef q, Ref phi) override;
  void velocity_residual(double t, ConstRef q, ConstRef w, Ref psi) override;
  void acceleration_bias(double t, ConstRef q, ConstRef w, Ref gamma) override;
  [[nodiscard]] bool has_curvature() const override { return full_->has_curvature(); }
  [[nodiscard]] const Sparse& mass_jacobian(double t, ConstRef q, ConstRef a) override;
  [[nodiscard]] const Sparse& constraint_force_jacobian(double t, ConstRef q, ConstRef w) override;
  [[nodiscard]] const Sparse& constraint_product_jacobian(double t, ConstRef q,
                                                          ConstRef a) override;
  [[nodiscard]] const Sparse& velocity_residual_jacobian(double t, ConstRef q, ConstRef w) override;
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_u(double t, ConstRef q,
                                                           ConstRef w) override;
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_v(double t, ConstRef q,
                                                           ConstRef w) override;
  [[nodiscard]] std::optional<double> energy(double t, ConstRef q, ConstRef w) override;

  /// The masters' values of full-space vectors (the reduced initial state).
  [[nodiscard]] Eigen::VectorXd restrict(const Eigen::VectorXd& x) const;
  /// u and u' in full space at (t, q, q').
  [[nodiscard]] std::pair<Eigen::VectorXd, Eigen::VectorXd> expand(double t, const ConstRef& q,
                                                                   const ConstRef& w) const;
  /// Every row's multiplier (m, scene order) at an output: the kept rows' λ_k as given, the
  /// eliminated rows' from the full equations with u'' = T q'' + G g_e''.
  [[nodiscard]] Eigen::VectorXd multipliers(double t, const ConstRef& q, const ConstRef& w,
                                            const ConstRef& qdd, const ConstRef& lambda_kept);

 private:
  struct Data {
    Sparse T, Tt, G;
    Sparse S;  ///< kept x m: selects the kept rows
    std::vector<int> masters, kept, eliminated;
    std::vector<bool> position;
    std::vector<TimeFunction> g;        ///< the eliminated rows' position-level right-hand sides
    bool rheonomic = false;             ///< some g_e is not identically zero
    bool constant = false;              ///< a linear model: the blocks below are formed once
    Sparse M, K, C, A;                  ///< M̂, Tᵀ K T, Tᵀ C T, A_k T (constant only)
    Sparse Ae;                          ///< the eliminated rows (constant)
    Eigen::SimplicialLDLT<Sparse> aat;  ///< A_e A_eᵀ
    int m = 0;                          ///< every row
  };

  /// g_e^(order)(t) mapped by G (n).
  [[nodiscard]] Eigen::VectorXd lifted(int order, double t) const;
  /// u_, v_ (and the full evaluator's load segment) at (t, q, w).
  void at(double t, const ConstRef& q);
  void at(double t, const ConstRef& q, const ConstRef& w);
  /// Rows k of `x` (m) for the kept rows.
  void select(const Eigen::VectorXd& x, Ref out) const;

  std::shared_ptr<const Data> data_;
  std::unique_ptr<MechanicalSystem> full_;
  Eigen::VectorXd u_, v_, f_, rows_;
  Sparse block_;
  /// The state-dependent blocks' maps (nonlinear models only): Tᵀ X T or S X T.
  FixedProduct mass_, stiffness_, damping_, a_, mass_jacobian_, constraint_force_jacobian_,
      constraint_product_jacobian_, velocity_residual_jacobian_, bias_jacobian_u_, bias_jacobian_v_;
};

}  // namespace condyn
