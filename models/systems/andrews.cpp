/// Andrews' squeezing mechanism (Test Set for IVP Solvers 2.4, problem "andrews"; equations,
/// parameters and reference in shared/reference/external-benchmarks.md §1): seven bodies in
/// generalized coordinates q = (β, Θ, γ, Φ, δ, Ω, ε), six loop-closure constraints g(q) = 0.
/// The test set writes 0 = M w − f + Gᵀλ, condyn's sign: λ and φ = g carry over unchanged.
///
/// Every constraint is a constant plus terms c·cos(θ) or c·sin(θ) of a phase θ = q_i (+ q_j), so
/// φ, A, γ and all curvature blocks follow exactly from the derivatives of sin and cos along the
/// phase direction s = e_i (+ e_j). The mass matrix and the forces are differentiated by hand
/// (tests/models/test_benchmark_systems.cpp checks every block against central differences).

#include <array>
#include <cmath>
#include <memory>

#include "models/systems/benchmarks.hpp"

namespace condyn {
namespace {

/// The test set's parameters (SI units).
namespace par {
constexpr double m1 = .04325, m2 = .00365, m3 = .02373, m4 = .00706, m5 = .07050, m6 = .00706,
                 m7 = .05498;
constexpr double xa = -.06934, ya = -.00227, xb = -.03635, yb = .03273, xc = .014, yc = .072,
                 c0 = 4530;
constexpr double I1 = 2.194e-6, I2 = 4.410e-7, I3 = 5.255e-6, I4 = 5.667e-7, I5 = 1.169e-5,
                 I6 = 5.667e-7, I7 = 1.912e-5;
constexpr double d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5, rr = 7e-3, ra = 92e-5,
                 l0 = 7785e-5, ss = 35e-3, sa = 1874e-5, sb = 1043e-5, sc = 18e-3, sd = 2e-2,
                 ta = 2308e-5, tb = 916e-5, u = 4e-2, ua = 1228e-5, ub = 449e-5, zf = 2e-2,
                 zt = 4e-2, fa = 1421e-5, mom = 33e-3;
/// Coefficients of the configuration-dependent inertia: M depends on Θ through c2 cosΘ, on Φ
/// through c4 sinΦ and on Ω through c6 sinΩ.
constexpr double c2 = m2 * da * rr, c4 = m4 * zt * (e - ea), c6 = -m6 * u * (zf - fa);
}  // namespace par

constexpr int kN = 7, kM = 6;
enum AndrewsDof { beta, Theta, gamma_, Phi, delta, Omega, epsilon };

/// One term c · sin(θ) or c · cos(θ) of row `row`, θ = q_i + q_j (j < 0: θ = q_i).
struct TrigTerm {
  int row;
  double c;
  bool sine;
  int i, j;
};

constexpr std::array<TrigTerm, 22> kTerms = {{
    {0, par::rr, false, beta, -1},        {0, -par::d, false, beta, Theta},
    {0, -par::ss, true, gamma_, -1},      {1, par::rr, true, beta, -1},
    {1, -par::d, true, beta, Theta},      {1, par::ss, false, gamma_, -1},
    {2, par::rr, false, beta, -1},        {2, -par::d, false, beta, Theta},
    {2, -par::e, true, Phi, delta},       {2, -par::zt, false, delta, -1},
    {3, par::rr, true, beta, -1},         {3, -par::d, true, beta, Theta},
    {3, par::e, false, Phi, delta},       {3, -par::zt, true, delta, -1},
    {4, par::rr, false, beta, -1},        {4, -par::d, false, beta, Theta},
    {4, -par::zf, false, Omega, epsilon}, {4, -par::u, true, epsilon, -1},
    {5, par::rr, true, beta, -1},         {5, -par::d, true, beta, Theta},
    {5, -par::zf, true, Omega, epsilon},  {5, par::u, false, epsilon, -1},
}};
constexpr std::array<double, kM> kRowConstant = {-par::xb, -par::yb, -par::xa,
                                                 -par::ya, -par::xa, -par::ya};

/// k-th derivative of sin (sine) or cos at θ, exact (no phase shifts by π/2 in floating point).
double trig_derivative(bool sine, int k, double theta) {
  switch ((k + (sine ? 0 : 1)) % 4) {
    case 0:
      return std::sin(theta);
    case 1:
      return std::cos(theta);
    case 2:
      return -std::sin(theta);
    default:
      return -std::cos(theta);
  }
}

/// s·x for a term's phase direction s = e_i (+ e_j); the phase itself is θ = s·q.
double along(const TrigTerm& term, const MechanicalSystem::ConstRef& x) {
  return x[term.i] + (term.j >= 0 ? x[term.j] : 0.0);
}

/// D.row(row) += x sᵀ.
void add_row(Eigen::MatrixXd& D, int row, const TrigTerm& term, double x) {
  D(row, term.i) += x;
  if (term.j >= 0) D(row, term.j) += x;
}

/// D += x s sᵀ.
void add_outer(Eigen::MatrixXd& D, const TrigTerm& term, double x) {
  add_row(D, term.i, term, x);
  if (term.j >= 0) add_row(D, term.j, term, x);
}

/// The spring between D (on body 3) and C: p = D − C as a function of γ, its γ-derivatives, the
/// length L and the force factor F = −c0 (L − l0)/L (the force on D is F p).
struct Spring {
  Eigen::Vector2d p, dp, ddp;
  double L, F;
  explicit Spring(double g) {
    const double c = std::cos(g), s = std::sin(g);
    p = {par::sd * c + par::sc * s + par::xb - par::xc,
         par::sd * s - par::sc * c + par::yb - par::yc};
    dp = {par::sc * c - par::sd * s, par::sd * c + par::sc * s};
    ddp = {-par::sd * c - par::sc * s, par::sc * c - par::sd * s};
    L = p.norm();
    F = -par::c0 * (L - par::l0) / L;
  }
};

class Andrews final : public MechanicalSystem {
 public:
  Andrews() {
    // The listed nonzeros of M (lower triangle) and their mirror images: the fixed pattern.
    constexpr std::array<std::pair<int, int>, 10> lower = {
        {{0, 0}, {1, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 3}, {4, 4}, {5, 5}, {6, 5}, {6, 6}}};
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(2 * lower.size());
    for (const auto& [i, j] : lower) {
      trip.emplace_back(i, j, 0.0);
      if (i != j) trip.emplace_back(j, i, 0.0);
    }
    M_.resize(kN, kN);
    M_.setFromTriplets(trip.begin(), trip.end());
    M_.makeCompressed();
  }

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<Andrews>(*this);
  }

  [[nodiscard]] int dofs() const override { return kN; }
  [[nodiscard]] int constraints() const override { return kM; }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return position_; }

  [[nodiscard]] const Sparse& mass(double /*t*/, ConstRef q) override {
    using namespace par;
    const double cT = std::cos(q[Theta]), sP = std::sin(q[Phi]), sO = std::sin(q[Omega]);
    const double ee = (e - ea) * (e - ea), ff = (zf - fa) * (zf - fa);
    const double M21 = m2 * (da * da - da * rr * cT) + I2;
    const double M54 = m4 * (ee + zt * (e - ea) * sP) + I4;
    const double M76 = m6 * (ff - u * (zf - fa) * sO) + I6;
    M_.coeffRef(0, 0) = m1 * ra * ra + m2 * (rr * rr - 2 * da * rr * cT + da * da) + I1 + I2;
    M_.coeffRef(1, 0) = M_.coeffRef(0, 1) = M21;
    M_.coeffRef(1, 1) = m2 * da * da + I2;
    M_.coeffRef(2, 2) = m3 * (sa * sa + sb * sb) + I3;
    M_.coeffRef(3, 3) = m4 * ee + I4;
    M_.coeffRef(4, 3) = M_.coeffRef(3, 4) = M54;
    M_.coeffRef(4, 4) =
        m4 * (zt * zt + 2 * zt * (e - ea) * sP + ee) + m5 * (ta * ta + tb * tb) + I4 + I5;
    M_.coeffRef(5, 5) = m6 * ff + I6;
    M_.coeffRef(6, 5) = M_.coeffRef(5, 6) = M76;
    M_.coeffRef(6, 6) =
        m6 * (ff - 2 * u * (zf - fa) * sO + u * u) + m7 * (ua * ua + ub * ub) + I6 + I7;
    return M_;
  }

  /// The driving moment on β, the spring on γ, and the velocity-dependent inertia terms.
  void force(double /*t*/, ConstRef q, ConstRef v, Ref f) override {
    using par::c2, par::c4, par::c6;
    const Spring sp(q[gamma_]);
    const double sT = std::sin(q[Theta]), cP = std::cos(q[Phi]), cO = std::cos(q[Omega]);
    f[beta] = par::mom - c2 * v[Theta] * (v[Theta] + 2 * v[beta]) * sT;
    f[Theta] = c2 * v[beta] * v[beta] * sT;
    f[gamma_] = sp.F * sp.p.dot(sp.dp);
    f[Phi] = c4 * v[delta] * v[delta] * cP;
    f[delta] = -c4 * v[Phi] * (v[Phi] + 2 * v[delta]) * cP;
    f[Omega] = c6 * v[epsilon] * v[epsilon] * cO;
    f[epsilon] = -c6 * v[Omega] * (v[Omega] + 2 * v[epsilon]) * cO;
  }

  /// −df/dq (D below is df/dq).
  [[nodiscard]] const Sparse& stiffness(double /*t*/, ConstRef q, ConstRef v) override {
    using par::c2, par::c4, par::c6;
    const Spring sp(q[gamma_]);
    const double cT = std::cos(q[Theta]), sP = std::sin(q[Phi]), sO = std::sin(q[Omega]);
    const double pdp = sp.p.dot(sp.dp);
    const double dF = -par::c0 * par::l0 * pdp / (sp.L * sp.L * sp.L);  // dF/dγ
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(kN, kN);
    D(beta, Theta) = -c2 * v[Theta] * (v[Theta] + 2 * v[beta]) * cT;
    D(Theta, Theta) = c2 * v[beta] * v[beta] * cT;
    D(gamma_, gamma_) = dF * pdp + sp.F * (sp.dp.squaredNorm() + sp.p.dot(sp.ddp));
    D(Phi, Phi) = -c4 * v[delta] * v[delta] * sP;
    D(delta, Phi) = c4 * v[Phi] * (v[Phi] + 2 * v[delta]) * sP;
    D(Omega, Omega) = -c6 * v[epsilon] * v[epsilon] * sO;
    D(epsilon, Omega) = c6 * v[Omega] * (v[Omega] + 2 * v[epsilon]) * sO;
    store_dense(stiffness_, -D);
    return stiffness_;
  }

  /// −df/dq' (D below is df/dq').
  [[nodiscard]] const Sparse& damping(double /*t*/, ConstRef q, ConstRef v) override {
    using par::c2, par::c4, par::c6;
    const double sT = std::sin(q[Theta]), cP = std::cos(q[Phi]), cO = std::cos(q[Omega]);
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(kN, kN);
    D(beta, beta) = -2 * c2 * v[Theta] * sT;
    D(beta, Theta) = -2 * c2 * (v[Theta] + v[beta]) * sT;
    D(Theta, beta) = 2 * c2 * v[beta] * sT;
    D(Phi, delta) = 2 * c4 * v[delta] * cP;
    D(delta, Phi) = -2 * c4 * (v[Phi] + v[delta]) * cP;
    D(delta, delta) = -2 * c4 * v[Phi] * cP;
    D(Omega, epsilon) = 2 * c6 * v[epsilon] * cO;
    D(epsilon, Omega) = -2 * c6 * (v[Omega] + v[epsilon]) * cO;
    D(epsilon, epsilon) = -2 * c6 * v[Omega] * cO;
    store_dense(damping_, -D);
    return damping_;
  }

  [[nodiscard]] const Sparse& constraint_jacobian(double /*t*/, ConstRef q) override {
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(kM, kN);
    for (const auto& term : kTerms)
      add_row(D, term.row, term, term.c * trig_derivative(term.sine, 1, along(term, q)));
    store_dense(A_, D);
    return A_;
  }

  void position_residual(double /*t*/, ConstRef q, Ref phi) override {
    for (int r = 0; r < kM; ++r) phi[r] = kRowConstant[static_cast<std::size_t>(r)];
    for (const auto& term : kTerms)
      phi[term.row] += term.c * trig_derivative(term.sine, 0, along(term, q));
  }

  /// Scleronomic rows: ψ = A v.
  void velocity_residual(double t, ConstRef q, ConstRef v, Ref psi) override {
    psi = constraint_jacobian(t, q) * v;
  }

  /// γ = −vᵀ φ_qq v = −Σ c trig''(θ) (s·v)².
  void acceleration_bias(double /*t*/, ConstRef q, ConstRef v, Ref gamma) override {
    gamma.setZero();
    for (const auto& term : kTerms) {
      const double sv = along(term, v);
      gamma[term.row] -= term.c * trig_derivative(term.sine, 2, along(term, q)) * sv * sv;
    }
  }

  [[nodiscard]] bool has_curvature() const override { return true; }

  [[nodiscard]] const Sparse& mass_jacobian(double /*t*/, ConstRef q, ConstRef a) override {
    using par::c2, par::c4, par::c6;
    const double sT = std::sin(q[Theta]), cP = std::cos(q[Phi]), cO = std::cos(q[Omega]);
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(kN, kN);
    // ∂M11/∂Θ = 2 c2 sinΘ, ∂M21/∂Θ = c2 sinΘ; ∂M54/∂Φ = c4 cosΦ, ∂M55/∂Φ = 2 c4 cosΦ;
    // ∂M76/∂Ω = c6 cosΩ, ∂M77/∂Ω = 2 c6 cosΩ.
    D(beta, Theta) = c2 * sT * (2 * a[beta] + a[Theta]);
    D(Theta, Theta) = c2 * sT * a[beta];
    D(Phi, Phi) = c4 * cP * a[delta];
    D(delta, Phi) = c4 * cP * (a[Phi] + 2 * a[delta]);
    D(Omega, Omega) = c6 * cO * a[epsilon];
    D(epsilon, Omega) = c6 * cO * (a[Omega] + 2 * a[epsilon]);
    store_dense(mass_jac_, D);
    return mass_jac_;
  }

  /// Σ_r w_r φ_r,qq = Σ w_r c trig''(θ) s sᵀ.
  [[nodiscard]] const Sparse& constraint_force_jacobian(double /*t*/, ConstRef q,
                                                        ConstRef w) override {
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(kN, kN);
    for (const auto& term : kTerms)
      add_outer(D, term, w[term.row] * term.c * trig_derivative(term.sine, 2, along(term, q)));
    store_dense(force_jac_, D);
    return force_jac_;
  }

  /// Row r: Σ c trig''(θ) (s·a) sᵀ.
  [[nodiscard]] const Sparse& constraint_product_jacobian(double /*t*/, ConstRef q,
                                                          ConstRef a) override {
    store_dense(product_jac_, curvature_rows(q, a, 2, 1.0, 1));
    return product_jac_;
  }

  /// Row r: Σ c trig''(θ) (s·v) sᵀ.
  [[nodiscard]] const Sparse& velocity_residual_jacobian(double /*t*/, ConstRef q,
                                                         ConstRef v) override {
    store_dense(psi_jac_, curvature_rows(q, v, 2, 1.0, 1));
    return psi_jac_;
  }

  /// Row r: −Σ c trig'''(θ) (s·v)² sᵀ.
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_u(double /*t*/, ConstRef q,
                                                           ConstRef v) override {
    store_dense(gamma_jac_u_, curvature_rows(q, v, 3, -1.0, 2));
    return gamma_jac_u_;
  }

  /// Row r: −2 Σ c trig''(θ) (s·v) sᵀ.
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_v(double /*t*/, ConstRef q,
                                                           ConstRef v) override {
    store_dense(gamma_jac_v_, curvature_rows(q, v, 2, -2.0, 1));
    return gamma_jac_v_;
  }

  /// ½ vᵀ M v + ½ c0 (L − l0)² − mom β: the moment is constant and the spring conservative.
  [[nodiscard]] std::optional<double> energy(double t, ConstRef q, ConstRef v) override {
    const Spring sp(q[gamma_]);
    const double stretch = sp.L - par::l0;
    return 0.5 * v.dot(mass(t, q) * v) + 0.5 * par::c0 * stretch * stretch - par::mom * q[beta];
  }

 private:
  /// Rows Σ scale · c trig^(k)(θ) (s·x)^power sᵀ (m x n).
  static Eigen::MatrixXd curvature_rows(const ConstRef& q, const ConstRef& x, int k, double scale,
                                        int power) {
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(kM, kN);
    for (const auto& term : kTerms) {
      const double sx = along(term, x);
      add_row(D, term.row, term,
              scale * term.c * trig_derivative(term.sine, k, along(term, q)) * std::pow(sx, power));
    }
    return D;
  }

  std::vector<bool> position_ = std::vector<bool>(kM, true);
  Sparse M_, stiffness_, damping_, A_, mass_jac_, force_jac_, product_jac_, psi_jac_, gamma_jac_u_,
      gamma_jac_v_;
};

}  // namespace

BenchmarkModel make_andrews() {
  BenchmarkModel b;
  b.system = std::make_shared<Andrews>();
  b.dof_names = {"beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon"};
  b.constraint_names = {"g1", "g2", "g3", "g4", "g5", "g6"};
  b.u0 =
      Eigen::VectorXd({{-0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449,
                        0.222668390165885884674473185609, 0.487364979543842550225598953530,
                        -0.222668390165885884674473185609, 1.23054744454982119249735015568}});
  b.v0 = Eigen::VectorXd::Zero(kN);
  b.t_end = 0.03;
  b.reference = [](double t) -> std::optional<PublishedReference> {
    if (std::abs(t - 0.03) > 1e-12 * 0.03) return std::nullopt;
    PublishedReference r;
    r.t = 0.03;
    r.u = Eigen::VectorXd({{0.1581077119629904e+2, -0.1575637105984298e+2, 0.4082224013073101e-1,
                            -0.5347301163226948e+0, 0.5244099658805304e+0, 0.5347301163226948e+0,
                            0.1048080741042263e+1}});
    r.v = Eigen::VectorXd({{0.1139920302151208e+4, -0.1424379294994111e+4, 0.1103291221937134e+2,
                            0.1929337464421385e+2, 0.5735699284790808e+0, -0.1929337464421385e+2,
                            0.3231791658026955e+0}});
    r.lambda =
        Eigen::VectorXd({{0.1991753333731910e+3, -0.2975531228015052e+2, 0.2306654119098399e+2,
                          0.3145271365475927e+2, 0.2264249232082739e+2, 0.1161740700019673e+2}});
    r.digits_u = 10;
    r.digits_v = 10;
    r.digits_lambda = 7;
    r.source = "Test Set for IVP Solvers 2.4, andrews: PSIDE at rtol = atol = 1e-14";
    return r;
  };
  b.description =
      "Andrews' squeezing mechanism (Test Set for IVP Solvers 2.4): 7 angles, 6 loop-closure "
      "constraints";
  return b;
}

}  // namespace condyn
