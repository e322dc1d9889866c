#include "models/systems/sleigh.hpp"

#include <cmath>
#include <memory>

namespace condyn {

namespace {

constexpr int kX = 0, kY = 1, kTheta = 2;

class Sleigh final : public MechanicalSystem {
 public:
  explicit Sleigh(SleighParameters p) : p_(std::move(p)), position_{false} {
    std::vector<Eigen::Triplet<double>> trip = {
        {kX, kX, p_.mass}, {kY, kY, p_.mass}, {kTheta, kTheta, p_.inertia}};
    M_.resize(3, 3);
    M_.setFromTriplets(trip.begin(), trip.end());
    zero_.resize(3, 3);
    A_.resize(1, 3);
    for (int c = 0; c < 3; ++c) A_.insert(0, c) = 0.0;  // every entry: a fixed pattern
    theta_column_.resize(3, 3);
    theta_column_.insert(kX, kTheta) = 0.0;
    theta_column_.insert(kY, kTheta) = 0.0;
    for (Sparse* row : {&product_u_, &psi_u_, &gamma_u_}) {  // one entry, d/dθ
      row->resize(1, 3);
      row->insert(0, kTheta) = 0.0;
    }
    gamma_v_.resize(1, 3);
    for (int c = 0; c < 3; ++c) gamma_v_.insert(0, c) = 0.0;
    conservative_ = true;
    for (const auto& l : p_.loads) conservative_ = conservative_ && l.value.is_constant();
  }

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<Sleigh>(*this);
  }

  [[nodiscard]] int dofs() const override { return 3; }
  [[nodiscard]] int constraints() const override { return 1; }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return position_; }
  [[nodiscard]] const Sparse& mass(double /*t*/, ConstRef /*u*/) override { return M_; }
  void force(double t, ConstRef /*u*/, ConstRef /*v*/, Ref f) override {
    f.setZero();
    for (const auto& l : p_.loads) l.add_to(f, l.value.derivative(0, t, steps_at(t)));
  }
  [[nodiscard]] const Sparse& stiffness(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    return zero_;
  }
  [[nodiscard]] const Sparse& damping(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    return zero_;
  }
  [[nodiscard]] const Sparse& constraint_jacobian(double /*t*/, ConstRef u) override {
    A_.valuePtr()[kX] = -std::sin(u[kTheta]);
    A_.valuePtr()[kY] = std::cos(u[kTheta]);
    A_.valuePtr()[kTheta] = p_.contact_offset;
    return A_;
  }
  void position_residual(double /*t*/, ConstRef /*u*/, Ref phi) override { phi.setZero(); }
  void velocity_residual(double /*t*/, ConstRef u, ConstRef v, Ref psi) override {
    psi[0] =
        -std::sin(u[kTheta]) * v[kX] + std::cos(u[kTheta]) * v[kY] + p_.contact_offset * v[kTheta];
  }
  void acceleration_bias(double /*t*/, ConstRef u, ConstRef v, Ref gamma) override {
    gamma[0] = v[kTheta] * forward_speed(u, v);
  }
  [[nodiscard]] bool has_curvature() const override { return true; }
  /// Aᵀw = w (−sin θ, cos θ, a): d/dθ = w (−cos θ, −sin θ, 0).
  [[nodiscard]] const Sparse& constraint_force_jacobian(double /*t*/, ConstRef u,
                                                        ConstRef w) override {
    theta_column_.valuePtr()[0] = -w[0] * std::cos(u[kTheta]);
    theta_column_.valuePtr()[1] = -w[0] * std::sin(u[kTheta]);
    return theta_column_;
  }
  [[nodiscard]] const Sparse& constraint_product_jacobian(double /*t*/, ConstRef u,
                                                          ConstRef a) override {
    product_u_.valuePtr()[0] = -forward_speed(u, a);
    return product_u_;
  }
  [[nodiscard]] const Sparse& velocity_residual_jacobian(double /*t*/, ConstRef u,
                                                         ConstRef v) override {
    psi_u_.valuePtr()[0] = -forward_speed(u, v);
    return psi_u_;
  }
  /// γ = θ' (cos θ x' + sin θ y'): d/dθ = θ' (−sin θ x' + cos θ y').
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_u(double /*t*/, ConstRef u,
                                                           ConstRef v) override {
    gamma_u_.valuePtr()[0] =
        v[kTheta] * (-std::sin(u[kTheta]) * v[kX] + std::cos(u[kTheta]) * v[kY]);
    return gamma_u_;
  }
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_v(double /*t*/, ConstRef u,
                                                           ConstRef v) override {
    gamma_v_.valuePtr()[kX] = v[kTheta] * std::cos(u[kTheta]);
    gamma_v_.valuePtr()[kY] = v[kTheta] * std::sin(u[kTheta]);
    gamma_v_.valuePtr()[kTheta] = forward_speed(u, v);
    return gamma_v_;
  }
  [[nodiscard]] std::optional<double> energy(double t, ConstRef u, ConstRef v) override {
    if (!conservative_) return std::nullopt;
    return 0.5 * v.dot(M_ * v) + energy_parts(t, u, v)->potential;
  }
  /// No springs: the constant loads' potential and the time-dependent ones' power.
  [[nodiscard]] std::optional<EnergyParts> energy_parts(double t, ConstRef u, ConstRef v) override {
    EnergyParts parts;
    add_load_energy(p_.loads, t, steps_at(t), u, v, parts.potential, parts.load_power);
    return parts;
  }

 private:
  /// The velocity component along the body axis, cos θ x' + sin θ y' (also for accelerations).
  static double forward_speed(const ConstRef& u, const ConstRef& v) {
    return std::cos(u[kTheta]) * v[kX] + std::sin(u[kTheta]) * v[kY];
  }

  SleighParameters p_;
  std::vector<bool> position_;
  Sparse M_, zero_;
  bool conservative_ = false;
  Sparse A_, theta_column_, product_u_, psi_u_, gamma_u_, gamma_v_;
};

}  // namespace

std::shared_ptr<const MechanicalSystem> make_sleigh(SleighParameters parameters) {
  return std::make_shared<Sleigh>(std::move(parameters));
}

}  // namespace condyn
