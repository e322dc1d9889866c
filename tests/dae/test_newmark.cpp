// The Newmark family (newmark, hht, generalized_alpha; dae/integrators/newmark_stepper.hpp): on a
// single-DOF oscillator the run equals the method's closed-form recurrence (Chung and Hulbert's
// amplification matrix applied n times) to roundoff for every parameter set; the recurrence's
// period elongation, algorithmic damping and spectral radius at infinity are the published ones;
// ρ∞ is reproduced on a stiff pair; the parameters are refused out of their stable range.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "dae/interface/scheme_not_applicable.hpp"
#include "dae/run/energy_balance.hpp"
#include "dae/run/run_plan.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/newmark_parameters.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/small_eigenvalues.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_newmark {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// One named parameter set: the scheme and its [solve] keys.
struct Case {
  const char* name;
  Scheme scheme;
  std::string keys;  ///< the [solve] table's parameter line
  AlphaParameters p;
  /// The spectral radius at h ω → ∞ the method is published with: Newmark's average
  /// acceleration 1 (the trapezoidal rule), HHT's (1 + α)/(1 − α) (Hilber, Hughes and Taylor
  /// 1977), the generalized-α's ρ∞ (Chung and Hulbert 1993: the parameters' defining property).
  double rho_inf;
};

std::vector<Case> cases() {
  return {
      {"newmark average acceleration", Scheme::newmark, "", newmark_parameters(0.25, 0.5), 1.0},
      {"hht alpha -0.1", Scheme::hht, "hht = { alpha = -0.1 }", hht_parameters(-0.1), 0.9 / 1.1},
      {"hht alpha -1/3", Scheme::hht, "hht = { alpha = -0.3333333333333333 }",
       hht_parameters(-1.0 / 3.0), 0.5},
      {"generalized-alpha rho 0", Scheme::generalized_alpha, "generalized_alpha = { rho_inf = 0 }",
       generalized_alpha_parameters(0.0), 0.0},
      {"generalized-alpha rho 0.5", Scheme::generalized_alpha,
       "generalized_alpha = { rho_inf = 0.5 }", generalized_alpha_parameters(0.5), 0.5},
      {"generalized-alpha rho 0.9", Scheme::generalized_alpha, "",
       generalized_alpha_parameters(0.9), 0.9},
      {"generalized-alpha rho 1", Scheme::generalized_alpha, "generalized_alpha = { rho_inf = 1 }",
       generalized_alpha_parameters(1.0), 1.0},
  };
}

/// Chung and Hulbert's (1993) recurrence for m ü + c u̇ + k u = 0 on the state X = [u; v; a]:
/// (1 − αm) a₁ + αm a₀ + c [(1 − αf) v₁ + αf v₀] + k [(1 − αf) u₁ + αf u₀] = 0 (m = 1),
/// u₁ = u₀ + h v₀ + h² [(½ − β) a₀ + β a₁], v₁ = v₀ + h [(1 − γ) a₀ + γ a₁]: L X₁ = R X₀.
Eigen::Matrix3d amplification(const AlphaParameters& p, double k, double c, double h) {
  Eigen::Matrix3d L, R;
  L << k * (1 - p.alpha_f), c * (1 - p.alpha_f), 1 - p.alpha_m,  //
      1, 0, -p.beta * h * h,                                     //
      0, 1, -p.gamma * h;
  R << -k * p.alpha_f, -c * p.alpha_f, -p.alpha_m,  //
      1, h, h * h * (0.5 - p.beta),                 //
      0, 1, h * (1 - p.gamma);
  return L.partialPivLu().solve(R);
}

/// The oscillator scene: unit mass, stiffness k, damping c, u(0) = 1, u'(0) = 0.5, `steps` steps
/// of h, an output at every step.
std::string oscillator(const Case& c, double k, double damping, double h, int steps) {
  return "[model]\ntype = \"matrix\"\ndofs = [\"x\"]\nmass = [[1.0]]\nstiffness = [[" +
         std::to_string(k) + "]]\ndamping = [[" + std::to_string(damping) +
         "]]\n[initial]\ndisplacement = { x = 1.0 }\nvelocity = { x = 0.5 }\n[solve]\nt_end = " +
         std::to_string(h * steps) + "\noutput_step = " + std::to_string(h) +
         "\nstep = " + std::to_string(h) + "\nscheme = \"" + to_string(c.scheme) + "\"\n" + c.keys +
         "\n";
}

}  // namespace

TEST_CASE("newmark family: the SDOF run is the method's amplification matrix applied n times") {
  // ω = 2 (k = 4), ξ = 0.05 (c = 0.2), h = 0.25 (h ω = 0.5), 200 steps: both the step and the
  // recurrence are one 3 x 3 solve per step, so they differ by an ulp or so per step, accumulated
  // linearly: eps per step of the state's size (observed 8e-16 to 4.4e-15 against 1.8e-13).
  const double k = 4.0, damping = 0.2, h = 0.25;
  const int steps = 200;
  for (const Case& c : cases()) {
    const std::string name = c.name;
    CAPTURE(name);
    const auto scene = test::built(parse_scene_text(oscillator(c, k, damping, h, steps), "o.toml"));
    const SolveResult r = test::solved(scene.model, scene.spec.solve);
    const Trajectory& traj = r.trajectory;
    REQUIRE(traj.t.size() == static_cast<std::size_t>(steps + 1));
    const Eigen::Matrix3d A = amplification(c.p, k, damping, h);
    Eigen::Vector3d X(1.0, 0.5, -k * 1.0 - damping * 0.5);  // a₀ = ü₀ from the equation
    const double tolerance = steps * kEps * X.cwiseAbs().maxCoeff();
    double worst = 0.0;
    for (int n = 0; n <= steps; ++n) {
      CHECK(traj.t[static_cast<std::size_t>(n)] == doctest::Approx(n * h).epsilon(1e-15));
      worst = std::max({worst, std::abs(traj.u(0, n) - X[0]), std::abs(traj.v(0, n) - X[1])});
      X = A * X;
    }
    MESSAGE(name << ": worst |run - recurrence| = " << worst << " (tolerance " << tolerance << ")");
    CHECK(worst <= tolerance);
  }
}

TEST_CASE("newmark family: period elongation, damping and rho_inf are the published ones") {
  // Undamped, Ω = h ω. Newmark with γ = ½ conserves energy (|λ| = 1, ξ̄ = 0) and its principal
  // roots have cos Ω̄ = 1 − Ω² / (2 (1 + β Ω²)) (Hughes 1987, The Finite Element Method, §9.3:
  // det A = 1 and ½ tr A of the (u, v) recurrence); for β = ¼ that is T̄/T = Ω / (2 atan(Ω/2)).
  // Roots of the 3 x 3 matrix agree with those to its eigen-solver's roundoff, 1e-12.
  constexpr double kRootTolerance = 1e-12;
  for (const double beta : {0.25, 1.0 / 6.0}) {
    for (const double omega_h : {0.1, 0.5, 1.0, 2.0}) {
      CAPTURE(beta);
      CAPTURE(omega_h);
      const Eigen::Matrix3d A = amplification(newmark_parameters(beta, 0.5), 1.0, 0.0, omega_h);
      const Eigen::Vector3cd roots = test::eigenvalues_3x3(A);
      int principal = 0;
      for (int i = 1; i < 3; ++i)
        if (std::abs(roots[i]) > std::abs(roots[principal])) principal = i;
      const std::complex<double> lambda = roots[principal];
      CHECK(std::abs(std::abs(lambda) - 1.0) <= kRootTolerance);  // ξ̄ = 0
      const double expected =
          std::acos(1.0 - omega_h * omega_h / (2.0 * (1.0 + beta * omega_h * omega_h)));
      CHECK(std::abs(std::abs(std::arg(lambda)) - expected) <= kRootTolerance);
      if (beta == 0.25) {
        const double elongation = omega_h / std::abs(std::arg(lambda));  // T̄ / T
        CHECK(std::abs(elongation - omega_h / (2.0 * std::atan(omega_h / 2.0))) <= kRootTolerance);
      }
    }
  }
  // Spectral radius at Ω → ∞ (Case::rho_inf), at Ω = 1e12: the roots meet at −ρ∞ there (a
  // double or triple root, which the eigen-solver splits by about ε^(1/3) of it), 4e-6 from it
  // still at Ω = 1e8 (observed), within 1e-6 from 1e10 on.
  constexpr double kLimitTolerance = 1e-6;
  for (const Case& c : cases()) {
    const std::string name = c.name;
    CAPTURE(name);
    const Eigen::Vector3cd roots = test::eigenvalues_3x3(amplification(c.p, 1.0, 0.0, 1e12));
    CHECK(std::abs(roots.cwiseAbs().maxCoeff() - c.rho_inf) <= kLimitTolerance);
  }
}

namespace {

/// The characteristic polynomial λ³ − 2A₁λ² + A₂λ − A₃ of the undamped step (m = 1, k = Ω², h = 1)
/// in closed form, derived from the method's equations as Chung and Hulbert (1993) derive theirs,
/// with D = (1 − αm) + β(1 − αf)Ω²: 2DA₁ = 2 − 3αm − Ω²[(1 − αf)(γ + ½) + (3αf − 2)β],
/// DA₂ = 1 − 3αm + Ω²[½ − γ + (1 − 3αf)β + 2αfγ], DA₃ = −αm + αfΩ²(γ − β − ½). For αm = 0,
/// αf = −α they are Hilber, Hughes and Taylor's (1977) A₁ = 1 − Ω²[(1 + α)(γ + ½) − αβ]/(2D),
/// A₂ = 1 − Ω²[γ − ½ + 2α(γ − β)]/D, A₃ = αΩ²(β − γ + ½)/D, D = 1 + (1 + α)βΩ² (also Hughes
/// 1987, §9.3); for αm = αf = 0, Newmark's (A₃ = 0).
Eigen::Vector3d invariants(const AlphaParameters& p, double omega_h) {
  const double w2 = omega_h * omega_h, am = p.alpha_m, af = p.alpha_f, b = p.beta, g = p.gamma;
  const double D = (1 - am) + b * (1 - af) * w2;
  return {(2 - 3 * am - w2 * ((1 - af) * (g + 0.5) + (3 * af - 2) * b)) / (2 * D),
          (1 - 3 * am + w2 * (0.5 - g + (1 - 3 * af) * b + 2 * af * g)) / D,
          (-am + af * w2 * (g - b - 0.5)) / D};
}

/// The principal root of λ³ − 2A₁λ² + A₂λ − A₃, one of the complex pair (the physical mode's;
/// the spurious root is real); its modulus and argument give the algorithmic damping ratio
/// ξ̄ = −ln|λ| / Ω̄ and the period elongation T̄/T = Ω / Ω̄, Ω̄ = arg λ.
std::complex<double> principal_root(const Eigen::Vector3d& a) {
  Eigen::Matrix3d companion;
  companion << 2 * a[0], -a[1], a[2],  //
      1, 0, 0,                         //
      0, 1, 0;
  const Eigen::Vector3cd roots = test::eigenvalues_3x3(companion);
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(roots[i].imag()) > std::abs(roots[k].imag())) k = i;
  return roots[k];
}

}  // namespace

TEST_CASE("newmark family: the step's characteristic polynomial is the published one") {
  // The run is the amplification matrix applied n times (above); its invariants, ½ trace, the sum
  // of principal 2 x 2 minors and the determinant, are the closed-form A₁, A₂, A₃ (invariants())
  // at every h ω: sums of a few O(1) products each side, so 64 eps (observed up to 6.7e-16).
  constexpr double kInvariantTolerance = 64 * kEps;
  for (const Case& c : cases()) {
    const std::string name = c.name;
    CAPTURE(name);
    for (const double omega_h : {0.05, 0.1, 0.5, 1.0, 2.0, 3.0, 10.0, 100.0}) {
      CAPTURE(omega_h);
      const Eigen::Matrix3d A = amplification(c.p, omega_h * omega_h, 0.0, 1.0);
      double minors = 0.0;
      for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        minors += A(j, j) * A(k, k) - A(j, k) * A(k, j);
      }
      const Eigen::Vector3d published = invariants(c.p, omega_h);
      CHECK(std::abs(0.5 * A.trace() - published[0]) <= kInvariantTolerance);
      CHECK(std::abs(minors - published[1]) <= kInvariantTolerance);
      CHECK(std::abs(A.determinant() - published[2]) <= kInvariantTolerance);
    }
  }
}

TEST_CASE("newmark family: algorithmic damping and period elongation at several h omega") {
  // From the published polynomial's principal root (principal_root) at h ω = 0.05 to 2 (below
  // linear acceleration's limit √12), the figures Hilber, Hughes and Taylor (1977, Fig. 2-3) and
  // Chung and Hulbert (1993, Fig. 1-2) plot: the family is second-order accurate, so the period
  // error T̄/T − 1 ~ c₂ Ω² and the damping ratio ξ̄ ~ c₃ Ω³ as Ω → 0 (halving Ω from 0.02 to 0.01
  // divides them by 4 and 8 to within 1 %: the next terms' share, observed at most 0.11 %, under
  // the generalized-α with ρ∞ = 0; 2.5 % from Ω = 0.1 to 0.05), and with
  // γ = ½ (average and linear acceleration, generalized-α ρ∞ = 1) ξ̄ = 0 (|λ| = 1 to roundoff).
  // Dissipation grows with Ω for the dissipative sets (ρ decreasing, ξ̄ increasing) and
  // at Ω = 2 is larger the smaller ρ∞ (generalized-α 0, 0.5, 0.9, 1; HHT α = −1/3, −0.1).
  constexpr double kOrderRatioTolerance = 0.01;
  constexpr double kUndampedTolerance = 1e-12;  // |ξ̄| of a unit-modulus root: the roots' roundoff
  const auto measured = [](const AlphaParameters& p, double omega_h) {
    const std::complex<double> root = principal_root(invariants(p, omega_h));
    const double phase = std::abs(std::arg(root));
    return std::pair{-std::log(std::abs(root)) / phase, omega_h / phase};  // ξ̄, T̄/T
  };
  std::vector<double> damping_at_2;
  for (const Case& c : cases()) {
    const std::string name = c.name;
    CAPTURE(name);
    const auto [xi_1, period_1] = measured(c.p, 0.02);
    const auto [xi_2, period_2] = measured(c.p, 0.01);
    CHECK(std::abs((period_1 - 1.0) / (period_2 - 1.0) / 4.0 - 1.0) <= kOrderRatioTolerance);
    if (c.p.gamma == 0.5) {
      for (const double omega_h : {0.05, 0.1, 0.5, 1.0, 2.0})
        CHECK(std::abs(measured(c.p, omega_h).first) <= kUndampedTolerance);
    } else {
      CHECK(std::abs(xi_1 / xi_2 / 8.0 - 1.0) <= kOrderRatioTolerance);
      double previous = 0.0;
      for (const double omega_h : {0.05, 0.1, 0.5, 1.0, 2.0}) {
        const auto [xi, period] = measured(c.p, omega_h);
        MESSAGE(name << ": h omega " << omega_h << ", damping ratio " << xi
                     << ", period elongation " << period - 1.0);
        CHECK(xi > previous);
        previous = xi;
      }
    }
    damping_at_2.push_back(measured(c.p, 2.0).first);
  }
  // cases(): [2] HHT −0.1, [3] HHT −1/3, [4..7] generalized-α ρ∞ = 0, 0.5, 0.9, 1.
  CHECK(damping_at_2[3] > damping_at_2[2]);
  CHECK(damping_at_2[4] > damping_at_2[5]);
  CHECK(damping_at_2[5] > damping_at_2[6]);
  CHECK(damping_at_2[6] > damping_at_2[7]);
}

TEST_CASE("newmark family: the energy balance shows the method's dissipation, as its roots say") {
  // An undamped, unloaded oscillator (ω = 0.5, h = 1: Ω = 0.5), 400 steps: nothing physical
  // dissipates or works, so the balance's error, T + V − (T + V)(0), is the method's own
  // dissipation, and D, W_loads and W_constraints stay 0. Average acceleration conserves the
  // energy of a linear model (roundoff: 1e-12 of E(0) over 400 steps); the others lose it as their
  // principal root's envelope, E(0) exp(−2 ξ̄ Ω̄ n), Ω̄ = arg λ (principal_root): the state's energy
  // moves about that envelope with the discrete phase and the spurious root by up to 6.9e-4 of
  // E(0) at n = 400 (observed, HHT α = −0.1; 5.9e-5 linear acceleration): 2e-3 kept.
  constexpr double kConservedTolerance = 1e-12, kEnvelopeTolerance = 2e-3;
  const double k = 0.25, h = 1.0;
  const int steps = 400;
  for (const Case& c : cases()) {
    const std::string name = c.name;
    CAPTURE(name);
    std::string text = oscillator(c, k, 0.0, h, steps);
    text.replace(text.find("velocity = { x = 0.5 }"), 22, "velocity = { x = 0.0 }");
    text += "[output]\nquantities = [\"displacement\", \"energy\"]\n";
    const auto scene = test::built(parse_scene_text(text, "energy.toml"));
    const SolveResult r =
        test::solved(scene.model, scene.spec.solve, hooks_for(scene.spec.output.quantities));
    REQUIRE(r.trajectory.balance.size() == r.trajectory.t.size());
    const EnergyBalance& last = r.trajectory.balance.back();
    const double e0 = last.initial;
    REQUIRE(e0 == doctest::Approx(0.5 * k).epsilon(1e-15));
    CHECK(last.dissipated == 0.0);
    CHECK(last.work_loads == 0.0);
    CHECK(last.work_constraints == 0.0);
    const double omega_h = std::sqrt(k) * h;
    const std::complex<double> root = principal_root(invariants(c.p, omega_h));
    const double envelope = std::pow(std::abs(root), 2.0 * steps);  // exp(−2 ξ̄ Ω̄ n)
    MESSAGE(name << ": E/E(0) = " << last.energy() / e0 << " at n = " << steps
                 << ", the roots' envelope " << envelope);
    CHECK(std::abs(last.error() - (last.energy() - e0)) <= kConservedTolerance * e0);
    if (c.p.gamma == 0.5 && c.p.beta == 0.25) {
      CHECK(std::abs(last.error()) <= kConservedTolerance * e0);
    } else {
      CHECK(std::abs(last.energy() / e0 - envelope) <= kEnvelopeTolerance);
    }
    if (c.p.gamma > 0.5) CHECK(last.error() < 0.0);  // the dissipative sets lose energy
  }
}

namespace {

/// The coefficients c of the linear recurrence of order q that the samples d₀ … d_{2q−1} follow
/// (Prony): d_{j+q} = Σ_i c_i d_{j+i}, whose characteristic polynomial z^q − Σ c_i z^i has the
/// step's roots; their product is (−1)^(q+1) c₀.
Eigen::VectorXd recurrence(const std::vector<double>& d, int q) {
  Eigen::MatrixXd H(q, q);
  Eigen::VectorXd next(q);
  for (int j = 0; j < q; ++j) {
    for (int i = 0; i < q; ++i) H(j, i) = d[static_cast<std::size_t>(j + i)];
    next[j] = d[static_cast<std::size_t>(j + q)];
  }
  return H.fullPivLu().solve(next);
}

}  // namespace

TEST_CASE("newmark family: rho_inf reproduced on a stiff pair") {
  // Two unit masses tied by a spring of k = 1e12, the first held by a constraint (a = 0, its
  // multiplier solved with the step at index 3): the second rings at ω = 1e6, started at
  // u_b = 1e-3 at rest; h = 0.01, so h ω = 1e4. Its motion follows the step's recurrence, whose
  // roots all tend to −ρ∞ as h ω grows (Chung and Hulbert's design: λ₁,₂ → −ρ∞ and the spurious
  // λ₃ = αf/(αf − 1) → −ρ∞; HHT's λ₃ = α/(1 + α)), so near-coincident: their product, the
  // recurrence's constant coefficient, is what the run measures well: −ρ∞³ for the
  // generalized-α, ρ∞² α/(1 + α) for HHT, ρ∞² where αm = αf (Newmark, ρ∞ = 1: a_n − ü_n keeps
  // its zero start, an order-2 recurrence). The closed form puts the product within 1e-8 of its
  // limit at h ω = 1e4; the fit's roundoff on near-coincident roots is the rest of
  // kProductTolerance.
  constexpr double kProductTolerance = 1e-6;
  const std::string pair = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[1e12, -1e12], [-1e12, 1e12]]
[[constraint]]
terms = { a = 1.0 }
[initial]
displacement = { b = 1e-3 }
[solve]
t_end = 0.08
output_step = 0.01
step = 0.01
)";
  for (const Case& c : cases()) {
    const std::string name = c.name;
    CAPTURE(name);
    const auto scene = test::built(parse_scene_text(
        pair + "scheme = \"" + to_string(c.scheme) + "\"\n" + c.keys + "\n", "pair.toml"));
    const SolveResult r = test::solved(scene.model, scene.spec.solve);
    std::vector<double> d;
    for (std::size_t n = 0; n < r.trajectory.t.size(); ++n)
      d.push_back(r.trajectory.u(1, static_cast<Eigen::Index>(n)));
    if (c.rho_inf == 0.0) {
      // Asymptotic annihilation: every root tends to 0, the high mode is gone after three steps
      // to the roots' 2e-3 at h ω = 1e4 (the closed form's), cubed.
      for (std::size_t n = 3; n < d.size(); ++n) CHECK(std::abs(d[n]) <= 1e-6 * std::abs(d[0]));
      continue;
    }
    double product = 0.0, expected = 0.0;
    if (c.p.alpha_m == c.p.alpha_f) {
      product = -recurrence(d, 2)[0];
      expected = c.rho_inf * c.rho_inf;
    } else {
      product = recurrence(d, 3)[0];
      const double alpha = -c.p.alpha_f;  // HHT's α
      expected = c.scheme == Scheme::hht ? c.rho_inf * c.rho_inf * alpha / (1.0 + alpha)
                                         : -std::pow(c.rho_inf, 3);
    }
    MESSAGE(name << ": product of the roots " << product << ", at infinity " << expected);
    CHECK(std::abs(product - expected) <= kProductTolerance);
  }
}

TEST_CASE(
    "newmark family: steps on the grid, a load step reached off it, one factorization per step") {
  // A unit oscillator (k = 4) under a unit step load switched on at t = 0.0355, between the grid
  // points 0.03 and 0.04 of h = 0.01: the steps are the grid's, plus the load step's time.
  const std::string scene = R"([model]
type = "matrix"
dofs = ["x"]
mass = [[1.0]]
stiffness = [[4.0]]
[[load]]
dof = "x"
value = { type = "step", amplitude = 1.0, start = 0.0355 }
[solve]
t_end = 0.1
output_step = 0.025
step = 0.01
scheme = "newmark"
)";
  const auto built = test::built(parse_scene_text(scene, "load.toml"));
  RunHooks hooks;
  hooks.record_steps = true;
  const SolveResult r = test::solved(built.model, built.spec.solve, hooks);
  std::vector<double> expected = {0.01, 0.02, 0.03, 0.0355};
  for (int k = 4; k <= 10; ++k) expected.push_back(0.01 * k);
  REQUIRE(r.trajectory.steps.size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    CHECK(r.trajectory.steps[k].t == doctest::Approx(expected[k]).epsilon(1e-14));
  }
  // The linear model's matrix depends on the step alone: factored for 0.01, 0.0055, 0.0045 and
  // 0.01 again (the last factorization is the one kept), not at every step.
  CHECK(r.summary.jacobian_evals == 4);
  CHECK(r.summary.restarts == 1);
  // Before the load, at rest: nothing moves; after it, the motion starts (u'' = 1 at t = 0.0355).
  CHECK(r.trajectory.u(0, 1) == 0.0);  // t = 0.025
  CHECK(r.trajectory.u(0, 2) > 0.0);   // t = 0.05
}

TEST_CASE("newmark family: parameters out of range and a misplaced step are refused") {
  const std::string head = R"([model]
type = "matrix"
dofs = ["x"]
mass = [[1.0]]
stiffness = [[1.0]]
[solve]
t_end = 1.0
output_step = 0.1
)";
  const struct {
    const char* keys;
    const char* key;  ///< the key the message must name
  } bad[] = {
      {"scheme = \"hht\"\nstep = 0.1\nhht = { alpha = -0.5 }", "solve.hht.alpha"},
      {"scheme = \"hht\"\nstep = 0.1\nhht = { alpha = 0.1 }", "solve.hht.alpha"},
      {"scheme = \"newmark\"\nstep = 0.1\nnewmark = { gamma = 0.4 }", "solve.newmark.gamma"},
      {"scheme = \"newmark\"\nstep = 0.1\nnewmark = { beta = 0 }", "solve.newmark.beta"},
      {"scheme = \"generalized_alpha\"\nstep = 0.1\ngeneralized_alpha = { rho_inf = 1.5 }",
       "solve.generalized_alpha.rho_inf"},
      {"scheme = \"generalized_alpha\"\nstep = 0.1\ngeneralized_alpha = { rho_inf = -0.1 }",
       "solve.generalized_alpha.rho_inf"},
      {"scheme = \"generalized_alpha\"\nstep = 0.1\n"
       "generalized_alpha = { alpha_m = 0.4, alpha_f = 0.2, beta = 0.3, gamma = 0.3 }",
       "solve.generalized_alpha"},
      {"scheme = \"generalized_alpha\"\nstep = 0.1\n"
       "generalized_alpha = { alpha_m = 0.0, alpha_f = 0.2 }",
       "solve.generalized_alpha"},
      // β below γ/2: conditionally stable (linear acceleration, the central difference), and a
      // γ whose γ/2 lies above the default β = ¼.
      {"scheme = \"newmark\"\nstep = 0.1\nnewmark = { beta = 0.16666666666666666 }",
       "solve.newmark.beta"},
      {"scheme = \"newmark\"\nnewmark = { beta = 0.3, gamma = 0.7 }", "solve.newmark.beta"},
      {"scheme = \"newmark\"\nnewmark = { gamma = 0.6 }", "solve.newmark.gamma"},
      {"scheme = \"newmark\"\nstep = 2.0", "solve.step"},
      {"scheme = \"newmark\"\nstep = -0.1", "solve.step"},
      {"scheme = \"ggl\"\nstep = 2.0", "solve.step"},
  };
  for (const auto& b : bad) {
    CAPTURE(b.keys);
    CHECK_THROWS_WITH_AS((void)parse_scene_text(head + b.keys + "\n", "bad.toml"),
                         doctest::Contains("bad.toml:"), SceneError);
    const std::string key = std::string(b.key) + ":";
    CHECK_THROWS_WITH_AS((void)parse_scene_text(head + b.keys + "\n", "bad.toml"),
                         doctest::Contains(key.c_str()), SceneError);
  }
  // The same rules for settings made in code (SolveSpec::validate, as the CLI's --step meets).
  SolveSpec s;
  s.t_end = 1.0;
  s.output_step = 0.1;
  s.scheme = Scheme::newmark;
  CHECK_NOTHROW(s.validate());  // no step: error-controlled
  s.step = 1.5;
  CHECK_THROWS_WITH_AS(s.validate(), doctest::Contains("solve.step"), std::invalid_argument);
  s.step = 0.1;
  s.newmark_family.newmark_gamma = 0.8;  // above twice the default β
  CHECK_THROWS_WITH_AS(s.validate(), doctest::Contains("solve.newmark.beta must be >= gamma/2"),
                       std::invalid_argument);
  s.newmark_family.newmark_beta = 0.4;
  CHECK_NOTHROW(s.validate());
  s.newmark_family.hht_alpha = -0.4;
  CHECK_THROWS_WITH_AS(s.validate(), doctest::Contains("solve.hht.alpha"), std::invalid_argument);
  // RATTLE has no error-controlled steps: without a step it is refused, naming the key.
  s.newmark_family = {};
  s.scheme = Scheme::rattle;
  s.step.reset();
  CHECK_THROWS_WITH_AS(s.validate(), doctest::Contains("solve.step: the rattle scheme"),
                       std::invalid_argument);
}

TEST_CASE("newmark family: a massless DOF outside the constraints is refused, naming it") {
  // Its start needs ü of every DOF, which [M Aᵀ; A 0] leaves undetermined for such a DOF.
  const std::string scene = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 0.0]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
[solve]
t_end = 1.0
output_step = 0.1
step = 0.01
)";
  for (const char* scheme : {"newmark", "hht", "generalized_alpha"}) {
    CAPTURE(scheme);
    const auto built =
        test::built(parse_scene_text(scene + "scheme = \"" + scheme + "\"\n", "massless.toml"));
    CHECK_THROWS_WITH_AS(
        (void)solve(built.model, built.spec.solve),
        doctest::Contains("massless DOFs outside the constraints yet (1, the first b)"),
        SchemeNotApplicable);
  }
}

TEST_CASE("newmark family: which parameter sets damp the highest frequencies") {
  // damps_high_frequencies against each set's published spectral radius at h ω → ∞ (the cases'
  // rho_inf): below 1 exactly when the set damps. Two Newmark sets beside them, against the
  // spectral radius of their amplification matrix at h ω = 1e4 (amplification(), above): γ = 0.6
  // with β = (γ + ½)²/4 damps (first order), γ = ½ with β = 0.3 does not (|λ| = 1 at every h ω).
  for (const Case& c : cases()) {
    CAPTURE(c.name);
    CHECK(damps_high_frequencies(c.p) == (c.rho_inf < 1.0));
  }
  const auto radius_at_infinity = [](const AlphaParameters& p) {
    constexpr double kOmegaH = 1e4;
    return test::eigenvalues_3x3(amplification(p, kOmegaH * kOmegaH, 0.0, 1.0))
        .cwiseAbs()
        .maxCoeff();
  };
  constexpr double kUnitRadius = 1e-6;  // ρ at 1e4 of an undamped set: 1 up to O(1/(h ω)²)
  for (const AlphaParameters& p : {newmark_parameters(0.3025, 0.6), newmark_parameters(0.3, 0.5)}) {
    CAPTURE(p.gamma);
    CHECK(damps_high_frequencies(p) == (radius_at_infinity(p) < 1.0 - kUnitRadius));
  }
  CHECK(damps_high_frequencies(newmark_parameters(0.3025, 0.6)));
  CHECK_FALSE(damps_high_frequencies(newmark_parameters(0.3, 0.5)));
}

}  // namespace test_newmark
