#pragma once
/// Point masses at truss nodes, in 2D or 3D, with large displacements:
///
///   bars      (geometry = "nonlinear") axial force N = EA (l − L)/L + c l' from the exact current
///             length l = |d|, d = x_j + u_j − x_i − u_i, L the rest length, e = d/l, l' = e·d'
///             (a dashpot c along the bar); tangent stiffness −∂f/∂u per node pair
///             (EA/L) e eᵀ + (N/l)(I − e eᵀ) + (c/l) e (d' − l' e)ᵀ, damping c e eᵀ;
///             (geometry = "linear") the small-displacement K u and C u' (c e₀e₀ᵀ, e₀ at the
///             reference positions, where the rest length is the nodes' distance);
///   mass      damping a0 M (Rayleigh's mass part: a drag on every node);
///   rigid     distance constraints φ = (|d|² − L²)/(2L), d = x_j + u_j − x_i − u_i, which equals
///             |d| − L to second order, so the drift reads as a length error; A = ±dᵀ/L,
///             γ = −|d'|²/L (the centripetal term);
///   loads     the scene's [[load]]s and gravity m g on every node (constant loads);
///   linear    the scene's [[constraint]] rows and supports (constant coefficients), first.
///
/// Every derivative is analytic (tests/models/test_nonlinear_models.cpp checks them against
/// finite differences).

#include <array>
#include <memory>
#include <vector>

#include "models/core/linear_rows.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/model.hpp"

namespace condyn {

struct PointMassLayout {
  int dimension = 2;
  std::vector<std::array<double, 3>> nodes;  ///< reference positions
  std::vector<double> masses;
  struct Bar {
    int i = 0, j = 0;  ///< 0-based nodes
    double EA = 0.0;
    double length = 0.0;  ///< rest length (bar) or length (rigid member), > 0
    double c = 0.0;       ///< axial dashpot (bars; >= 0)
  };
  std::vector<Bar> bars;
  bool nonlinear_geometry = false;
  std::vector<Bar> rods;      ///< rigid members (EA and c unused)
  double mass_damping = 0.0;  ///< a0 of the damping a0 M (>= 0)
  std::vector<Load> loads;
  std::vector<Constraint> linear_rows;  ///< scene order, before the rods
};

class PointMassSystem final : public MechanicalSystem {
 public:
  explicit PointMassSystem(PointMassLayout layout);

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<PointMassSystem>(*this);
  }

  [[nodiscard]] int dofs() const override { return n_; }
  [[nodiscard]] int constraints() const override { return m_; }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return position_; }
  [[nodiscard]] const Sparse& mass(double /*t*/, ConstRef /*u*/) override { return M_; }
  void force(double t, ConstRef u, ConstRef v, Ref f) override;
  [[nodiscard]] const Sparse& stiffness(double t, ConstRef u, ConstRef v) override;
  [[nodiscard]] const Sparse& damping(double t, ConstRef u, ConstRef v) override;
  [[nodiscard]] const Sparse& constraint_jacobian(double t, ConstRef u) override;
  void position_residual(double t, ConstRef u, Ref phi) override;
  void velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) override;
  void acceleration_bias(double t, ConstRef u, ConstRef v, Ref gamma) override;

  [[nodiscard]] bool has_curvature() const override { return !layout_.rods.empty(); }
  [[nodiscard]] const Sparse& constraint_force_jacobian(double t, ConstRef u, ConstRef w) override;
  [[nodiscard]] const Sparse& constraint_product_jacobian(double t, ConstRef u,
                                                          ConstRef a) override;
  [[nodiscard]] const Sparse& velocity_residual_jacobian(double t, ConstRef u, ConstRef v) override;
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_v(double t, ConstRef u,
                                                           ConstRef v) override;
  [[nodiscard]] std::optional<double> energy(double t, ConstRef u, ConstRef v) override;
  /// The strain energy of the bars (from their rest lengths) with the potential of the constant
  /// loads (gravity), the power the dashpots and a0 M dissipate (vᵀC v), and the power of the
  /// time-dependent loads: the balance of any loading.
  [[nodiscard]] std::optional<EnergyParts> energy_parts(double t, ConstRef u, ConstRef v) override;
  /// The largest |reference coordinate| of the nodes and the longest member.
  [[nodiscard]] double coordinate_scale() const override;
  /// The size of the values the rod rows compute at the start, their longest length: a row takes
  /// X_j − X_i + u_j − u_i (the nodes' exact difference) and its length, so its roundoff is eps
  /// times it (dae/formulations/model_scales.hpp, GGL's μ); 0 without rods.
  [[nodiscard]] double row_length_scale() const override;

 private:
  /// d = x_j + u_j − x_i − u_i for a member (dimension entries).
  [[nodiscard]] Eigen::VectorXd separation(const PointMassLayout::Bar& b, const ConstRef& u) const;
  [[nodiscard]] Eigen::VectorXd relative(const PointMassLayout::Bar& b, const ConstRef& v) const;
  /// |d| = s |d/s| with s the power of 2 of d's largest entry: the squares neither overflow (from
  /// 1e154 up) nor underflow (below 1e-154), and where they did not, the same bits as d.norm()
  /// (scaling by a power of 2 is exact, and so commutes with each rounding).
  [[nodiscard]] static double distance(const Eigen::VectorXd& d);
  [[nodiscard]] int dof(int node, int direction) const {
    return node * layout_.dimension + direction;
  }
  /// Adds c · (row vector r) at row `row`, columns of node j (+r) and node i (−r).
  void add_row_pair(std::vector<Eigen::Triplet<double>>& trip, int row,
                    const PointMassLayout::Bar& b, const Eigen::VectorXd& r) const;
  /// The damping force's magnitude c l' along a bar (0 when c = 0), and l' itself.
  [[nodiscard]] double dashpot_force(const PointMassLayout::Bar& b, const Eigen::VectorXd& e,
                                     const ConstRef& v) const {
    return b.c == 0.0 ? 0.0 : b.c * e.dot(relative(b, v));
  }
  /// Adds the 2x2 block pattern [B −B; −B B] on the DOFs of nodes i and j.
  void add_block_pair(std::vector<Eigen::Triplet<double>>& trip, const PointMassLayout::Bar& b,
                      const Eigen::MatrixXd& B) const;
  [[nodiscard]] static const Sparse& assemble(Sparse& S, int rows, int cols,
                                              std::vector<Eigen::Triplet<double>>& trip);

  PointMassLayout layout_;
  int n_, m_, linear_count_;
  LinearRows linear_;
  std::vector<bool> position_;
  Sparse M_, K_linear_, no_damping_;
  /// Damped at all (a dashpot or a0 > 0); C of linear geometry (a0 M + Σ c e₀e₀ᵀ), constant.
  bool damped_ = false;
  Sparse C_linear_;
  bool conservative_ = false;
  Sparse stiffness_, damping_, A_, force_jac_, product_jac_, psi_jac_, gamma_jac_v_;
  std::vector<Eigen::Triplet<double>> trip_;
};

}  // namespace condyn
