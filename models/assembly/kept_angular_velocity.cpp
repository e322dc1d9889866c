#include "models/assembly/kept_angular_velocity.hpp"

#include <stdexcept>
#include <utility>

namespace condyn {

namespace {

class KeptRotations final : public MechanicalSystem {
 public:
  KeptRotations(std::shared_ptr<MechanicalSystem> base, std::vector<KeptRotationRow> kept)
      : base_(std::move(base)), kept_(std::move(kept)) {
    position_rows_ = base_->position_rows();
    position_rows_.resize(position_rows_.size() + kept_.size(), false);
  }

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<KeptRotations>(std::shared_ptr<MechanicalSystem>(base_->clone()),
                                           kept_);
  }
  [[nodiscard]] int dofs() const override { return base_->dofs(); }
  [[nodiscard]] int constraints() const override {
    return base_->constraints() + static_cast<int>(kept_.size());
  }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return position_rows_; }
  [[nodiscard]] const Sparse& mass(double t, ConstRef u) override { return base_->mass(t, u); }

  [[nodiscard]] const Sparse& constraint_jacobian(double t, ConstRef u) override {
    const Sparse& A = base_->constraint_jacobian(t, u);
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(static_cast<std::size_t>(A.nonZeros()) + 9 * kept_.size());
    for (int k = 0; k < A.outerSize(); ++k)
      for (Sparse::InnerIterator it(A, k); it; ++it)
        trip.emplace_back(it.row(), it.col(), it.value());
    for (std::size_t r = 0; r < kept_.size(); ++r) {
      const auto row = static_cast<int>(A.rows() + static_cast<Eigen::Index>(r));
      const auto grad = gradient(kept_[r], u);
      for (std::size_t j = 0; j < grad.size(); ++j)
        trip.emplace_back(row, kept_[r].axes[j], grad[j]);
    }
    jacobian_.resize(constraints(), dofs());
    jacobian_.setFromTriplets(trip.begin(), trip.end());
    return jacobian_;
  }
  void position_residual(double t, ConstRef u, Ref phi) override {
    const int m = base_->constraints();
    base_->position_residual(t, u, phi.head(m));
    phi.tail(static_cast<Eigen::Index>(kept_.size())).setZero();
  }
  void velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) override {
    const int m = base_->constraints();
    base_->velocity_residual(t, u, v, psi.head(m));
    for (std::size_t r = 0; r < kept_.size(); ++r) {
      const auto grad = gradient(kept_[r], u);
      double omega = 0.0;  // ω is linear in the velocities: its gradient times them
      for (std::size_t j = 0; j < grad.size(); ++j) omega += grad[j] * v[kept_[r].axes[j]];
      psi[m + static_cast<Eigen::Index>(r)] = omega - kept_[r].value;
    }
  }

  // Not evaluated by the projection (the only user of this system).
  void force(double /*t*/, ConstRef /*u*/, ConstRef /*v*/, Ref /*f*/) override { unused(); }
  [[nodiscard]] const Sparse& stiffness(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    unused();
  }
  [[nodiscard]] const Sparse& damping(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    unused();
  }
  void acceleration_bias(double /*t*/, ConstRef /*u*/, ConstRef /*v*/, Ref /*gamma*/) override {
    unused();
  }

 private:
  [[noreturn]] static void unused() {
    throw std::logic_error(
        "the kept angular velocities' system serves the initial projection only");
  }

  /// ∂ω/∂(the row's axes' velocities) at u: 2D (−u_y, u_x); 3D ½ of the component's row of
  /// [R_k]× for each column k.
  static std::vector<double> gradient(const KeptRotationRow& row, ConstRef u) {
    if (row.axes.size() == 2) return {-u[row.axes[1]], u[row.axes[0]]};
    std::vector<double> g(9, 0.0);
    const int i = row.component, j = (i + 1) % 3, k = (i + 2) % 3;
    for (std::size_t col = 0; col < 3; ++col) {
      // (a × b)_i = a_j b_k − a_k b_j with a = R_col, b = R_col'; entries 3 col + c.
      const auto entry = [col](int c) { return 3 * col + static_cast<std::size_t>(c); };
      const auto at = [&](int c) { return u[row.axes[entry(c)]]; };
      g[entry(k)] = 0.5 * at(j);
      g[entry(j)] = -0.5 * at(k);
    }
    return g;
  }

  std::shared_ptr<MechanicalSystem> base_;
  std::vector<KeptRotationRow> kept_;
  std::vector<bool> position_rows_;
  Sparse jacobian_;
};

}  // namespace

std::unique_ptr<MechanicalSystem> with_kept_rotations(std::unique_ptr<MechanicalSystem> base,
                                                      std::vector<KeptRotationRow> kept) {
  return std::make_unique<KeptRotations>(std::shared_ptr<MechanicalSystem>(std::move(base)),
                                         std::move(kept));
}

}  // namespace condyn
