/// The pendulum of period 2 (shared/reference/external-benchmarks.md §3): unit mass on a rod of
/// unit length in Cartesian coordinates (x, y), released at rest from (1, 0). With
/// g = (2 K(1/√2))² the period is exactly 2, so the state at t = 2N is exactly the initial one.
///
/// φ = (x² + y² − 1)/2 makes A = (x, y), so x'' = −λ x as in the reference's equations: λ is the
/// rod's tension per unit length, in condyn's sign.

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "models/systems/benchmarks.hpp"

namespace condyn {
namespace {

/// g = (2 K(1/√2))² with K(k) = π / (2 AGM(1, √(1 − k²))), i.e. (π / AGM(1, 1/√2))²: the
/// arithmetic-geometric mean converges quadratically; iterated in long double to its precision,
/// then rounded once.
double pendulum_gravity() {
  using real = long double;
  real a = 1, b = std::sqrt(real(0.5));
  for (int k = 0; k < 16 && a - b > std::numeric_limits<real>::epsilon() * a; ++k) {
    const real mean = (a + b) / 2;
    b = std::sqrt(a * b);
    a = mean;
  }
  const real ratio = std::numbers::pi_v<real> / a;
  return static_cast<double>(ratio * ratio);
}

class Pendulum final : public MechanicalSystem {
 public:
  explicit Pendulum(double g) : g_(g) {
    M_.resize(2, 2);
    M_.setIdentity();
    M_.makeCompressed();
    no_terms_.resize(2, 2);
  }

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<Pendulum>(*this);
  }

  [[nodiscard]] int dofs() const override { return 2; }
  [[nodiscard]] int constraints() const override { return 1; }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return position_; }
  [[nodiscard]] const Sparse& mass(double /*t*/, ConstRef /*u*/) override { return M_; }
  void force(double /*t*/, ConstRef /*u*/, ConstRef /*v*/, Ref f) override { f << 0.0, -g_; }
  /// Constant gravity: 2 x 2 without entries.
  [[nodiscard]] const Sparse& stiffness(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    return no_terms_;
  }
  [[nodiscard]] const Sparse& damping(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    return no_terms_;
  }

  [[nodiscard]] const Sparse& constraint_jacobian(double /*t*/, ConstRef u) override {
    store_dense(A_, u.transpose());
    return A_;
  }
  void position_residual(double /*t*/, ConstRef u, Ref phi) override {
    phi[0] = (u.squaredNorm() - 1) / 2;
  }
  void velocity_residual(double /*t*/, ConstRef u, ConstRef v, Ref psi) override {
    psi[0] = u.dot(v);
  }
  /// γ = −|u'|² (the centripetal term).
  void acceleration_bias(double /*t*/, ConstRef /*u*/, ConstRef v, Ref gamma) override {
    gamma[0] = -v.squaredNorm();
  }

  [[nodiscard]] bool has_curvature() const override { return true; }
  /// d(u w)/du = w I.
  [[nodiscard]] const Sparse& constraint_force_jacobian(double /*t*/, ConstRef /*u*/,
                                                        ConstRef w) override {
    store_dense(force_jac_, w[0] * Eigen::Matrix2d::Identity());
    return force_jac_;
  }
  /// d(u·a)/du = aᵀ.
  [[nodiscard]] const Sparse& constraint_product_jacobian(double /*t*/, ConstRef /*u*/,
                                                          ConstRef a) override {
    store_dense(product_jac_, a.transpose());
    return product_jac_;
  }
  /// d(u·v)/du = vᵀ.
  [[nodiscard]] const Sparse& velocity_residual_jacobian(double /*t*/, ConstRef /*u*/,
                                                         ConstRef v) override {
    store_dense(psi_jac_, v.transpose());
    return psi_jac_;
  }
  /// γ does not depend on u (the default empty block); dγ/du' = −2 vᵀ.
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_v(double /*t*/, ConstRef /*u*/,
                                                           ConstRef v) override {
    store_dense(gamma_jac_v_, -2.0 * v.transpose());
    return gamma_jac_v_;
  }

  /// ½ |v|² + g y.
  [[nodiscard]] std::optional<double> energy(double /*t*/, ConstRef u, ConstRef v) override {
    return 0.5 * v.squaredNorm() + g_ * u[1];
  }

 private:
  double g_;
  std::vector<bool> position_ = {true};
  Sparse M_, no_terms_;
  Sparse A_, force_jac_, product_jac_, psi_jac_, gamma_jac_v_;
};

}  // namespace

BenchmarkModel make_pendulum() {
  BenchmarkModel b;
  b.system = std::make_shared<Pendulum>(pendulum_gravity());
  b.dof_names = {"x", "y"};
  b.constraint_names = {"rod"};
  b.u0 = Eigen::VectorXd({{1.0, 0.0}});
  b.v0 = Eigen::VectorXd::Zero(2);
  b.t_end = 2.0;
  b.reference = [](double t) -> std::optional<PublishedReference> {
    const double N = std::round(t / 2);
    if (N < 1 || std::abs(t - 2 * N) > 1e-12 * std::abs(t)) return std::nullopt;
    PublishedReference r;
    r.t = 2 * N;
    r.u = Eigen::VectorXd({{1.0, 0.0}});
    r.v = Eigen::VectorXd::Zero(2);
    r.lambda = Eigen::VectorXd::Zero(1);  // at rest at (1, 0): |v|² − λ − y g = 0 gives λ = 0
    r.digits_u = r.digits_v = r.digits_lambda = 15;
    r.source = "exact: the period is 2 by the choice g = (2 K(1/sqrt 2))^2";
    return r;
  };
  b.description =
      "Pendulum of period 2 (unit mass and length, g = (2K(1/sqrt 2))^2): x, y and one rod "
      "constraint; exact state at t = 2N";
  return b;
}

}  // namespace condyn
