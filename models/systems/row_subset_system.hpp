#pragma once
/// A MechanicalSystem with only some of another's constraint rows: [solve] redundant = "drop" on
/// a nonlinear model keeps a maximal independent subset of its rows (chosen at t = 0,
/// models/assembly/rank_check.cpp) and integrates
///
///   M(t, u) u'' = f(t, u, u') − A_K(t, u)ᵀ λ_K,   φ_K(t, u) = 0, ψ_K = 0, A_K u'' = γ_K
///
/// where K are the kept rows: every row block of the wrapped system (A, φ, ψ, γ and the m x n
/// curvature blocks) restricted to K, in the wrapped order; d(Aᵀw)/du takes the kept multipliers
/// with 0 on the dropped rows; M, f, K, C, d(M a)/du and the energy are the wrapped system's. It
/// knows nothing of the model type (trusses, mechanisms): any system and any list of kept rows.

#include <memory>
#include <vector>

#include "models/core/mechanical_system.hpp"

namespace condyn {

class RowSubsetSystem final : public MechanicalSystem {
 public:
  /// Keeps rows `kept` of `wrapped` (strictly increasing indices below wrapped.constraints()),
  /// evaluating a clone of it. Throws std::invalid_argument for any other list.
  RowSubsetSystem(const MechanicalSystem& wrapped, std::vector<int> kept);
  RowSubsetSystem(const RowSubsetSystem& other);
  ~RowSubsetSystem() override = default;
  RowSubsetSystem& operator=(const RowSubsetSystem&) = delete;

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<RowSubsetSystem>(*this);
  }

  [[nodiscard]] int dofs() const override { return inner_->dofs(); }
  [[nodiscard]] int constraints() const override { return static_cast<int>(rows_->kept.size()); }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return rows_->position; }
  /// The wrapped system's rows that are kept, in its numbering.
  [[nodiscard]] const std::vector<int>& kept_rows() const { return rows_->kept; }
  /// The wrapped system, every row (this evaluator's own clone of it).
  [[nodiscard]] const MechanicalSystem& wrapped() const { return *inner_; }

  [[nodiscard]] const Sparse& mass(double t, ConstRef u) override;
  void force(double t, ConstRef u, ConstRef v, Ref f) override;
  [[nodiscard]] const Sparse& stiffness(double t, ConstRef u, ConstRef v) override;
  [[nodiscard]] const Sparse& damping(double t, ConstRef u, ConstRef v) override;
  [[nodiscard]] const Sparse& constraint_jacobian(double t, ConstRef u) override;
  void position_residual(double t, ConstRef u, Ref phi) override;
  void velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) override;
  void acceleration_bias(double t, ConstRef u, ConstRef v, Ref gamma) override;

  [[nodiscard]] bool has_curvature() const override { return inner_->has_curvature(); }
  [[nodiscard]] const Sparse& mass_jacobian(double t, ConstRef u, ConstRef a) override;
  [[nodiscard]] const Sparse& constraint_force_jacobian(double t, ConstRef u, ConstRef w) override;
  [[nodiscard]] const Sparse& constraint_product_jacobian(double t, ConstRef u,
                                                          ConstRef a) override;
  [[nodiscard]] const Sparse& velocity_residual_jacobian(double t, ConstRef u, ConstRef v) override;
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_u(double t, ConstRef u,
                                                           ConstRef v) override;
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_v(double t, ConstRef u,
                                                           ConstRef v) override;

  [[nodiscard]] std::optional<double> energy(double t, ConstRef u, ConstRef v) override;
  [[nodiscard]] std::optional<EnergyParts> energy_parts(double t, ConstRef u, ConstRef v) override;
  [[nodiscard]] double coordinate_scale() const override { return inner_->coordinate_scale(); }
  [[nodiscard]] double row_length_scale() const override { return inner_->row_length_scale(); }

 private:
  /// The constant part, shared by every clone.
  struct Rows {
    std::vector<int> kept;
    std::vector<int> new_row;  ///< per wrapped row: its index among the kept ones, or -1
    std::vector<bool> position;
  };

  /// The kept rows of a wrapped m x n block whose pattern does not change between calls: the
  /// result's pattern and the source of each of its entries are made once (again when the
  /// block's pattern differs from the last one's), each call copies the values.
  class RowSelection {
   public:
    const Sparse& operator()(const Rows& rows, const Sparse& block);

   private:
    void plan(const Rows& rows, const Sparse& block);
    Sparse result_;
    std::vector<Sparse::StorageIndex> starts_, indices_;  ///< the block's pattern at the plan
    std::vector<Eigen::Index> source_;  ///< per result entry, its index in the block
  };

  /// Evaluations outside an integration segment, or inside one, reach the wrapped system alike.
  MechanicalSystem& inner(double t);
  /// The kept entries of all_rows_ in `out`.
  void select(Ref out) const;

  std::shared_ptr<const Rows> rows_;
  std::unique_ptr<MechanicalSystem> inner_;
  Eigen::VectorXd all_rows_;  ///< scratch: a value per wrapped row
  RowSelection a_, product_jacobian_, velocity_jacobian_, bias_jacobian_u_, bias_jacobian_v_;
};

}  // namespace condyn
