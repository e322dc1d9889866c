/// The car axis (Test Set for IVP Solvers 2.4, problem "caraxis"; shared/reference/
/// external-benchmarks.md §2): two wheels at (xl, yl) and (xr, yr), each on a spring of rest
/// length L0, the left one anchored at the origin, the right one at the road point (xb, yb)(t);
/// the left wheel stays on the line through the origin normal to (xb, yb), the axle has length L.
///
/// The test set writes k u'' = f + Gᵀλ with g1 = xb xl + yb yl, g2 = |l − r|² − L²; condyn writes
/// M u'' = f − Aᵀλ with φ = (g1, g2) unchanged, so λ_condyn = −λ_testset (the reference below is
/// negated accordingly). The road makes g1 rheonomic: ψ and γ carry xb', yb', xb'', yb''.

#include <cmath>
#include <memory>

#include "models/systems/benchmarks.hpp"

namespace condyn {
namespace {

namespace par {
constexpr double eps = 1e-2, mass = 10, L = 1, L0 = 0.5, r = 0.1, w = 10, g = 1;
constexpr double k = mass * eps * eps / 2;  ///< the wheels' mass
}  // namespace par

enum CarAxisDof { xl, yl, xr, yr };

/// The road point (xb, yb) = (√(L² − yb²), r sin(w t)) and its first two time derivatives.
struct Road {
  double xb, yb, dxb, dyb, ddxb, ddyb;
  explicit Road(double t) {
    yb = par::r * std::sin(par::w * t);
    dyb = par::r * par::w * std::cos(par::w * t);
    ddyb = -par::w * par::w * yb;
    xb = std::sqrt(par::L * par::L - yb * yb);
    dxb = -yb * dyb / xb;                              // from xb xb' + yb yb' = 0
    ddxb = -(dyb * dyb + yb * ddyb + dxb * dxb) / xb;  // and its derivative
  }
};

/// Force of a spring of rest length L0 on the end at p (the other end at 0): (L0 − |p|) p/|p|.
Eigen::Vector2d spring_force(const Eigen::Vector2d& p) {
  const double l = p.norm();
  return (par::L0 - l) / l * p;
}

/// Its Jacobian: L0 (I/|p| − p pᵀ/|p|³) − I.
Eigen::Matrix2d spring_force_jacobian(const Eigen::Vector2d& p) {
  const double l = p.norm();
  return par::L0 / l * (Eigen::Matrix2d::Identity() - p * p.transpose() / (l * l)) -
         Eigen::Matrix2d::Identity();
}

class CarAxis final : public MechanicalSystem {
 public:
  CarAxis() {
    M_.resize(4, 4);
    M_.setIdentity();
    M_ *= par::k;
    M_.makeCompressed();
    no_terms_.resize(4, 4);
  }

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<CarAxis>(*this);
  }

  [[nodiscard]] int dofs() const override { return 4; }
  [[nodiscard]] int constraints() const override { return 2; }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return position_; }
  [[nodiscard]] const Sparse& mass(double /*t*/, ConstRef /*u*/) override { return M_; }

  void force(double t, ConstRef u, ConstRef /*v*/, Ref f) override {
    const Road road(t);
    f.head<2>() = spring_force(u.head<2>());
    f.tail<2>() = spring_force(u.tail<2>() - Eigen::Vector2d(road.xb, road.yb));
    f[yl] -= par::k * par::g;
    f[yr] -= par::k * par::g;
  }

  /// −df/du: the springs' Jacobians negated.
  [[nodiscard]] const Sparse& stiffness(double t, ConstRef u, ConstRef /*v*/) override {
    const Road road(t);
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(4, 4);
    D.topLeftCorner<2, 2>() = -spring_force_jacobian(u.head<2>());
    D.bottomRightCorner<2, 2>() =
        -spring_force_jacobian(u.tail<2>() - Eigen::Vector2d(road.xb, road.yb));
    store_dense(stiffness_, D);
    return stiffness_;
  }
  /// No damping: 4 x 4 without entries.
  [[nodiscard]] const Sparse& damping(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) override {
    return no_terms_;
  }

  /// Rows (xb, yb, 0, 0) and 2 (dx, dy, −dx, −dy), d = l − r.
  [[nodiscard]] const Sparse& constraint_jacobian(double t, ConstRef u) override {
    const Road road(t);
    const double dx = u[xl] - u[xr], dy = u[yl] - u[yr];
    Eigen::MatrixXd D(2, 4);
    D << road.xb, road.yb, 0, 0, 2 * dx, 2 * dy, -2 * dx, -2 * dy;
    store_dense(A_, D);
    return A_;
  }

  void position_residual(double t, ConstRef u, Ref phi) override {
    const Road road(t);
    const double dx = u[xl] - u[xr], dy = u[yl] - u[yr];
    phi[0] = road.xb * u[xl] + road.yb * u[yl];
    phi[1] = dx * dx + dy * dy - par::L * par::L;
  }

  void velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) override {
    const Road road(t);
    psi[0] = road.xb * v[xl] + road.yb * v[yl] + road.dxb * u[xl] + road.dyb * u[yl];
    psi[1] = 2 * ((u[xl] - u[xr]) * (v[xl] - v[xr]) + (u[yl] - u[yr]) * (v[yl] - v[yr]));
  }

  /// γ1 = −2 (xb' ul + yb' vl) − (xb'' xl + yb'' yl), γ2 = −2 |l' − r'|².
  void acceleration_bias(double t, ConstRef u, ConstRef v, Ref gamma) override {
    const Road road(t);
    const double dvx = v[xl] - v[xr], dvy = v[yl] - v[yr];
    gamma[0] = -2 * (road.dxb * v[xl] + road.dyb * v[yl]) - (road.ddxb * u[xl] + road.ddyb * u[yl]);
    gamma[1] = -2 * (dvx * dvx + dvy * dvy);
  }

  /// The springs' energy and gravity's potential; the road moves the right spring's anchor b(t),
  /// which works on the system at the rate ∂V/∂t = f_r · b' (f_r the spring's force on the
  /// wheel): reported as the work of the loads. The road row's own work (it is rheonomic) is the
  /// constraint forces' (EnergyTerms).
  [[nodiscard]] std::optional<EnergyParts> energy_parts(double t, ConstRef u,
                                                        ConstRef /*v*/) override {
    const Road road(t);
    const Eigen::Vector2d p = u.tail<2>() - Eigen::Vector2d(road.xb, road.yb);
    const auto spring = [](const Eigen::Vector2d& d) {
      const double stretch = d.norm() - par::L0;
      return 0.5 * stretch * stretch;
    };
    EnergyParts parts;
    parts.potential = spring(u.head<2>()) + spring(p) + par::k * par::g * (u[yl] + u[yr]);
    parts.load_power = spring_force(p).dot(Eigen::Vector2d(road.dxb, road.dyb));
    return parts;
  }

  [[nodiscard]] bool has_curvature() const override { return true; }

  /// Only the axle row depends on u: d(2 w2 (d, −d))/du = 2 w2 [I −I; −I I].
  [[nodiscard]] const Sparse& constraint_force_jacobian(double /*t*/, ConstRef /*u*/,
                                                        ConstRef w) override {
    Eigen::MatrixXd D(4, 4);
    const Eigen::Matrix2d I = 2 * w[1] * Eigen::Matrix2d::Identity();
    D << I, -I, -I, I;
    store_dense(force_jac_, D);
    return force_jac_;
  }

  [[nodiscard]] const Sparse& constraint_product_jacobian(double /*t*/, ConstRef /*u*/,
                                                          ConstRef a) override {
    store_dense(product_jac_, axle_row(a, 2.0, 0.0, 0.0));
    return product_jac_;
  }

  [[nodiscard]] const Sparse& velocity_residual_jacobian(double t, ConstRef /*u*/,
                                                         ConstRef v) override {
    const Road road(t);
    store_dense(psi_jac_, axle_row(v, 2.0, road.dxb, road.dyb));
    return psi_jac_;
  }

  [[nodiscard]] const Sparse& acceleration_bias_jacobian_u(double t, ConstRef /*u*/,
                                                           ConstRef v) override {
    const Road road(t);
    store_dense(gamma_jac_u_, axle_row(v, 0.0, -road.ddxb, -road.ddyb));
    return gamma_jac_u_;
  }

  [[nodiscard]] const Sparse& acceleration_bias_jacobian_v(double t, ConstRef /*u*/,
                                                           ConstRef v) override {
    const Road road(t);
    store_dense(gamma_jac_v_, axle_row(v, -4.0, -2 * road.dxb, -2 * road.dyb));
    return gamma_jac_v_;
  }

 private:
  /// The 2 x 4 block with road row (c0, c1, 0, 0) and axle row scale · (dx, dy, −dx, −dy) of the
  /// relative vector x_l − x_r.
  static Eigen::MatrixXd axle_row(const ConstRef& x, double scale, double c0, double c1) {
    const double dx = scale * (x[xl] - x[xr]), dy = scale * (x[yl] - x[yr]);
    Eigen::MatrixXd D(2, 4);
    D << c0, c1, 0, 0, dx, dy, -dx, -dy;
    return D;
  }

  std::vector<bool> position_ = {true, true};
  Sparse M_, no_terms_;
  Sparse stiffness_, A_, force_jac_, product_jac_, psi_jac_, gamma_jac_u_, gamma_jac_v_;
};

}  // namespace

BenchmarkModel make_car_axis() {
  BenchmarkModel b;
  b.system = std::make_shared<CarAxis>();
  b.dof_names = {"xl", "yl", "xr", "yr"};
  b.constraint_names = {"road", "axle"};
  b.u0 = Eigen::VectorXd({{0.0, 0.5, 1.0, 0.5}});
  b.v0 = Eigen::VectorXd({{-0.5, 0.0, -0.5, 0.0}});
  b.t_end = 3.0;
  b.reference = [](double t) -> std::optional<PublishedReference> {
    if (std::abs(t - 3.0) > 1e-12 * 3.0) return std::nullopt;
    PublishedReference r;
    r.t = 3.0;
    r.u = Eigen::VectorXd({{0.493455784275402809122e-1, 0.496989460230171153861,
                            0.104174252488542151681e+1, 0.373911027265361256927}});
    r.v = Eigen::VectorXd({{-0.770583684040972357970e-1, 0.744686658723778553466e-2,
                            0.175568157537232222276e-1, 0.770341043779251976443}});
    // y9, y10 negated: condyn's f_con = −Aᵀλ against the test set's +Gᵀλ.
    r.lambda = Eigen::VectorXd({{0.473688659084893324729e-2, 0.110468033125734368808e-2}});
    r.digits_u = 10;  // the 21-digit set satisfies the constraints to round-off
    r.digits_v = 10;
    r.digits_lambda = 7;
    r.source = "Test Set for IVP Solvers 2.4, caraxis: 21-digit reference at t = 3";
    return r;
  };
  b.description =
      "Car axis (Test Set for IVP Solvers 2.4): 2 wheels on springs, 1 rheonomic road constraint, "
      "1 axle length";
  return b;
}

}  // namespace condyn
