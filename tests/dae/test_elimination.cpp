#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "dae/formulations/reduced_ode.hpp"
#include "dae/formulations/reduced_system.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/symmetric_products.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/compare.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/embedded_scenes.hpp"

using namespace condyn;

namespace test_elimination {

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Assembly of integer-valued matrices from EA = 200√2 written to 15 digits (3.5e-17 relative off,
// below eps): a few roundings, 8 eps relative to max|K| (observed 8.9e-17).
constexpr double kAssemblyTolerance = 8 * kEps;
// Algebraic identities of the transform (A T = 0, A G = I): a few ulps of O(1) entries, 8 eps
// (observed exact). Against the zero matrix the relative tolerance scales to 0: A T must be
// exactly 0, as it is.
constexpr double kIdentityTolerance = 8 * kEps;

Model scene_model(const std::string& text) { return build_model(parse_scene_text(text, "test")); }
test::BuiltScene chapter_model(const std::string& name) {
  return test::built(parse_scene_text(embedded_scene(name).text, name));
}

}  // namespace

TEST_CASE("truss2d assembles the chapter's master stiffness" * doctest::test_suite("smoke")) {
  // reference/chapter-truss.md, "Master stiffness" (derived there by hand).
  Eigen::MatrixXd K(6, 6);
  K << 20, 10, -10, 0, -10, -10,  //
      10, 10, 0, 0, -10, -10,     //
      -10, 0, 10, 0, 0, 0,        //
      0, 0, 0, 5, 0, -5,          //
      -10, -10, 0, 0, 10, 10,     //
      -10, -10, 0, -5, 10, 15;
  const Model model = chapter_model("chapter_5_5_1").model;
  CONDYN_CHECK_CLOSE(Eigen::MatrixXd(*model.K), K, kAssemblyTolerance);
  Eigen::VectorXd m(6);
  m << 5, 5, 3, 3, 4, 4;
  CONDYN_CHECK_CLOSE(Eigen::MatrixXd(model.M), Eigen::MatrixXd(m.asDiagonal()), 0.0);
}

TEST_CASE("master-slave transform: A T = 0, A G = I, pivoted slave choice" *
          doctest::test_suite("smoke")) {
  Eigen::MatrixXd a(3, 6);
  a << 1, 2, 0, 0, -1, 0,  //
      0, 0, 3, 1, 0, 0,    //
      0.5, 0, 0, 0, 1, 1;
  const Eigen::SparseMatrix<double> A = a.sparseView();
  const MasterSlave ms = master_slave_transform(A);
  CHECK(ms.slaves.size() == 3);
  CHECK(ms.masters.size() == 3);
  CONDYN_CHECK_CLOSE(Eigen::MatrixXd(A * ms.T), Eigen::MatrixXd::Zero(3, 3), kIdentityTolerance);
  CONDYN_CHECK_CLOSE(Eigen::MatrixXd(A * ms.G), Eigen::MatrixXd::Identity(3, 3),
                     kIdentityTolerance);

  // Single-freedom constraints: the slaves are exactly the constrained DOFs (direct elimination).
  const Model model = chapter_model("chapter_5_5_1").model;
  const MasterSlave sfc = master_slave_transform(model.A);
  CHECK(sfc.slaves == std::vector<int>{0, 1, 3});
  CHECK(sfc.masters == std::vector<int>{2, 4, 5});
}

TEST_CASE("master-slave transform refuses slaves that cannot carry the constraints") {
  Eigen::MatrixXd a(2, 4);
  a << 1, 1, 0, 0,  //
      0, 0, 1, 1;
  const Eigen::SparseMatrix<double> A = a.sparseView();
  CHECK_THROWS_WITH_AS((void)master_slave_transform(A, {0, 1}),
                       doctest::Contains("slave block condition number"), std::invalid_argument);
  CHECK_NOTHROW((void)master_slave_transform(A, {1, 2}));
  CHECK_THROWS_AS((void)master_slave_transform(A, {1, 1}), std::invalid_argument);
}

TEST_CASE("master-slave transform: a row's scale is no ill-conditioning") {
  // 1e12 u1 = 0 beside u2 = 0 (a 'big number' support, as some FE exports write one): two
  // independent, well-posed groups, refused before as a slave block of condition 1e12.
  Eigen::MatrixXd a(2, 3);
  a << 1e12, 0, 0,  //
      0, 1, 0;
  const Eigen::SparseMatrix<double> A = a.sparseView();
  const MasterSlave ms = master_slave_transform(A);
  CHECK(ms.slaves == std::vector<int>{0, 1});
  CHECK(Eigen::MatrixXd(A * ms.T).isZero(0.0));
  CHECK(Eigen::MatrixXd(A * ms.G).isApprox(Eigen::MatrixXd::Identity(2, 2), 1e-15));
  // Within one group too: rows scaled by 1e12 and 1 of a well-conditioned pair.
  Eigen::MatrixXd b(2, 3);
  b << 1e12, -1e12, 0,  //
      0, 1, -1;
  const MasterSlave scaled = master_slave_transform(b.sparseView());
  CHECK(Eigen::MatrixXd(b * Eigen::MatrixXd(scaled.G))
            .isApprox(Eigen::MatrixXd::Identity(2, 2), 1e-15));
}

TEST_CASE("reduced ODE Jacobian agrees with central differences of the residual") {
  // A damped, rheonomic case so that every block (K̂, Ĉ, M̂) is present.
  const std::string text = R"([model]
type = "matrix"
dofs = ["a", "b", "c"]
mass = [[2.0, 0.1, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 3.0]]
stiffness = [[5.0, -2.0, 0.0], [-2.0, 4.0, -1.0], [0.0, -1.0, 2.0]]
damping = [[0.3, 0.0, 0.0], [0.0, 0.2, 0.1], [0.0, 0.1, 0.4]]
[[constraint]]
terms = { a = 1.0, c = -2.0 }
value = { type = "harmonic", amplitude = 0.1, omega = 1.5 }
[initial]
velocity = { a = 0.15 }
[solve]
t_end = 1.0
output_step = 0.5
)";
  const Model model = scene_model(text);
  const ReducedSystem reduced = reduce(model);
  const ReducedOde ode(model, reduced);
  const int n = ode.size();
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(n, 0.3, -0.7);
  Eigen::VectorXd yp = Eigen::VectorXd::LinSpaced(n, -0.2, 0.9);
  const double t = 0.37, cj = 12.5;
  Eigen::SparseMatrix<double> J = ode.jacobian_pattern().matrix();
  ode.jacobian(t, y, yp, cj, J);
  // The residual is linear: central differences (h = 1e-6) are exact up to their roundoff
  // eps |F| / h, with |F| ≲ n max|J| for states of size ≤ 1: n eps / h (observed 3.7e-12).
  CONDYN_CHECK_CLOSE(Eigen::MatrixXd(J), test::finite_difference_jacobian(ode, t, y, yp, cj),
                     n * kEps / 1e-6);
}

TEST_CASE("a large reduced ODE's residual in one pass on two lanes equals the three products") {
  // 100 × 100 nodes: M̂ and K̂ alone hold over 2e5 entries together, so the residual is formed by
  // rows on two lanes (models/core/symmetric_products.hpp); under Rayleigh damping Ĉ w comes from M̂
  // and K̂ (reduced_ode.cpp), under none it is left out.
  for (const std::string damping : {"damping = { rayleigh = [0.3, 0.02] }\n", ""}) {
    const Model model = scene_model(test::lattice(100, 100, damping, ""));
    REQUIRE(model.has_damping() == !damping.empty());
    CHECK(model.rayleigh.has_value() == !damping.empty());
    const ReducedSystem reduced = reduce(model);
    REQUIRE(static_cast<double>(reduced.M.nonZeros() + reduced.K.nonZeros() +
                                reduced.C.nonZeros()) >= kLanedProductFewestEntries);
    const ReducedOde ode(model, reduced);
    const int n = ode.size(), nm = n / 2;
    const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(n, 0.3, -0.7);
    const Eigen::VectorXd yp = Eigen::VectorXd::LinSpaced(n, -0.2, 0.9);
    Eigen::VectorXd r(n);
    ode.residual(0.2, y, yp, r);
    Eigen::VectorXd expected(n);
    expected.head(nm) = yp.head(nm) - y.tail(nm);
    expected.tail(nm) =
        reduced.M * yp.tail(nm) + reduced.K * y.head(nm) - reduced.forces(model, 0.2, 0.2);
    if (model.has_damping()) expected.tail(nm) += reduced.C * y.tail(nm);
    // Sums in another order (and a₀ M̂ + a₁ K̂ for Ĉ): roundoff of rows whose terms are at most
    // |K̂| + |Ĉ| + |M̂| times states of size ≤ 1.
    const double scale =
        (reduced.K.cwiseAbs() * Eigen::VectorXd::Ones(nm)).maxCoeff() +
        (reduced.M.cwiseAbs() * Eigen::VectorXd::Ones(nm)).maxCoeff() +
        (model.has_damping() ? (reduced.C.cwiseAbs() * Eigen::VectorXd::Ones(nm)).maxCoeff() : 0.0);
    CHECK((r - expected).lpNorm<Eigen::Infinity>() <= 64 * kEps * scale);
  }
}

TEST_CASE("a load step after t = 0 is crossed with a stop and restart, under every scheme" *
          doctest::test_suite("smoke")) {
  // Two unit masses x, y tied together (y = x), a spring 4 on x, and F H(t − 1) on x: the pair
  // moves as one mass 2 on the spring, x = F/k (1 − cos(ω (t − 1))) for t ≥ 1, ω = √2. The tie
  // pulls y along with f_con = m_y x'', which jumps at the step, so the multiplier schemes must
  // re-solve λ there.
  const std::string text = R"([model]
type = "matrix"
dofs = ["x", "y"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[4.0, 0.0], [0.0, 0.0]]
[[load]]
dof = "x"
value = { type = "step", amplitude = 3.0, start = 1.0 }
[[constraint]]
name = "tie"
terms = { y = 1.0, x = -1.0 }
[solve]
t_end = 4.0
output_step = 0.5
rtol = 1e-10
atol = 1e-12
)";
  const SceneSpec spec = parse_scene_text(text, "test");
  const Model model = build_model(spec);
  const double w = std::sqrt(2.0);
  for (Scheme scheme : {Scheme::elimination, Scheme::index1, Scheme::baumgarte, Scheme::ggl}) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult result = test::solved(model, test::under(spec.solve, scheme));
    const Trajectory& run = result.trajectory;
    const SolveSummary& summary = result.summary;
    CHECK(summary.restarts == 1);
    double worst_x = 0.0, worst_r = 0.0;
    for (std::size_t k = 0; k < run.t.size(); ++k) {
      const double t = run.t[k];
      const double x = t < 1.0 ? 0.0 : 0.75 * (1.0 - std::cos(w * (t - 1.0)));
      // The tie pulls y along: f_con on y = m_y x'' = x'' (right limit at the step).
      const double xdd = t < 1.0 ? 0.0 : 0.75 * w * w * std::cos(w * (t - 1.0));
      const auto c = static_cast<Eigen::Index>(k);
      worst_x = std::max(worst_x, std::abs(run.u(0, c) - x));
      worst_r = std::max(worst_r, std::abs(run.reaction(1, c) - xdd));
    }
    // Global error of a 2-period run on O(1) values: kGlobalErrorFactor (1e3,
    // validation/references/suite.hpp) × the scene's rtol 1e-10 (observed up to 7.2e-10 in
    // x, 8.2e-9 in f_con).
    CHECK(worst_x <= 1e3 * 1e-10);
    CHECK(worst_r <= 1e3 * 1e-10);
    CHECK(run.u(0, 2) == 0.0);  // t = 1.0: the step has not moved anything yet
    // Right limit F/2, from one solve of O(1) numbers at the restart (observed exact).
    CHECK(run.reaction(1, 2) == doctest::Approx(1.5).epsilon(64 * kEps));
  }
  // Projection: every accepted step is projected, in both segments (CVODE's own count restarts
  // after the re-initialisation, and the first segment's projections were lost).
  const SolveResult projected = test::solved(model, test::under(spec.solve, Scheme::projection));
  CHECK(projected.summary.restarts == 1);
  const std::string notes = projected.summary.notes_text();
  CAPTURE(notes);
  REQUIRE(notes.find(" projections onto the constraints") != std::string::npos);
  CHECK(std::stol(notes) >= projected.summary.steps);
}

TEST_CASE("the elimination path refuses massless master DOFs nothing holds, by name") {
  // b has neither mass, stiffness nor a constraint (one held by stiffness is integrated:
  // tests/dae/test_held_massless.cpp).
  const std::string text = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 0.0]]
stiffness = [[2.0, 0.0], [0.0, 0.0]]
[solve]
t_end = 1.0
output_step = 0.5
)";
  // The builder refuses it first, as bad input naming the DOF and the key (issue 10, item 16);
  // the elimination's own guard stays for models built otherwise.
  CHECK_THROWS_WITH_AS(
      (void)scene_model(text),
      doctest::Contains("model: DOF 'b' has neither mass nor stiffness nor damping"), SceneError);
}

TEST_CASE("the dense linear solver gives the KLU answer") {
  const test::BuiltScene built = chapter_model("chapter_5_6_2");
  SolveSpec settings = test::under(built.spec.solve, Scheme::elimination);
  const SolveResult klu = test::solved(built.model, settings);
  settings.dense_linear_solver = true;
  const Trajectory dense = test::solved(built.model, settings).trajectory;
  // Same Newton iterations with a different LU: a few ulps per step, accumulated over the run's
  // steps at most linearly (1417 steps: 3e-13; observed 1.2e-14).
  CONDYN_CHECK_CLOSE(dense.u, klu.trajectory.u, static_cast<double>(klu.summary.steps) * kEps);
}

TEST_CASE("elimination of a model whose every DOF is prescribed: no unknowns, exact rows") {
  // Two DOFs held by a harmonic drive and a tie: master-slave elimination leaves no unknowns,
  // which IDA refuses ("initial ewt component = 0.0"); the rows follow from the time alone:
  // u = 0.5 sin 2t on both DOFs, and the reactions close M u'' + C u' + K u = f + f_con.
  const SceneSpec spec = parse_scene_text(R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 2.0]]
stiffness = [[3.0, -1.0], [-1.0, 1.0]]
damping = { rayleigh = [0.1, 0.01] }
[[load]]
dof = "b"
value = 1.0
[[constraint]]
name = "drive"
terms = { a = 1.0 }
value = { type = "harmonic", amplitude = 0.5, omega = 2.0 }
[[constraint]]
name = "hold"
terms = { a = 1.0, b = -1.0 }
[initial]
velocity = { a = 1.0, b = 1.0 }
[solve]
scheme = "elimination"
t_end = 2.0
output_step = 0.25
)",
                                          "prescribed.toml");
  const Model model = build_model(spec);
  RunHooks hooks;
  hooks.accelerations = true;
  const SolveResult r = test::solved(model, spec.solve, hooks);
  CHECK(r.summary.unknowns == 0);
  CHECK(r.summary.steps == 0);
  REQUIRE(r.trajectory.t.size() == 9);
  Eigen::MatrixXd M(2, 2), K(2, 2);
  M << 1, 0, 0, 2;
  K << 3, -1, -1, 1;
  const Eigen::MatrixXd C = 0.1 * M + 0.01 * K;
  const Eigen::Vector2d f(0.0, 1.0), ones(1.0, 1.0);
  for (std::size_t k = 0; k < r.trajectory.t.size(); ++k) {
    const double t = r.trajectory.t[k];
    CAPTURE(t);
    const Eigen::Vector2d u = 0.5 * std::sin(2 * t) * ones, v = std::cos(2 * t) * ones,
                          a = -2.0 * std::sin(2 * t) * ones;
    // Time functions evaluated and a 2 x 2 system: a few ulps of O(1) values, 16 eps.
    CHECK((r.trajectory.u.col(static_cast<Eigen::Index>(k)) - u).norm() <= 16 * kEps);
    CHECK((r.trajectory.v.col(static_cast<Eigen::Index>(k)) - v).norm() <= 16 * kEps);
    CHECK((r.trajectory.acceleration.col(static_cast<Eigen::Index>(k)) - a).norm() <= 16 * kEps);
    const Eigen::Vector2d reaction = M * a + C * v + K * u - f;
    CHECK((r.trajectory.reaction.col(static_cast<Eigen::Index>(k)) - reaction).norm() <= 64 * kEps);
  }
}

TEST_CASE("elimination of a slow velocity drive keeps the digits of its integral") {
  // u' = sin(ωt + 0.3) with ω = 1e-12 prescribes u = ∫₀ᵗ sin(ωs + 0.3) ds; written as
  // (cos 0.3 − cos(ωt + 0.3))/ω its two terms of 10¹² cancelled to 4 digits (u(0) = 6e-5). Every
  // DOF is prescribed, so the rows are the time function alone: its Taylor series (three terms,
  // the next below 1e-30 relative) to a few ulps, 16 eps relative.
  for (const char* omega : {"1e-12", "1e-14", "-1e-12", "1e-6"}) {
    CAPTURE(omega);
    const SceneSpec spec = parse_scene_text(std::string(R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 2.0]]
stiffness = [[3.0, -1.0], [-1.0, 1.0]]
[[constraint]]
name = "drive"
level = "velocity"
terms = { a = 1.0 }
value = { type = "harmonic", amplitude = 1.0, phase = 0.3, omega = )") +
                                                omega + R"( }
[[constraint]]
name = "hold"
terms = { a = 1.0, b = -1.0 }
[initial]
velocity = { a = 0.29552020666133955, b = 0.29552020666133955 }
[solve]
scheme = "elimination"
t_end = 2.0
output_step = 0.5
)",
                                            "slow_drive.toml");
    const SolveResult r = test::solved(build_model(spec), spec.solve);
    REQUIRE(r.trajectory.t.size() == 5);
    const double w = std::stod(omega);
    for (std::size_t k = 0; k < r.trajectory.t.size(); ++k) {
      const double t = r.trajectory.t[k];
      CAPTURE(t);
      const double u = std::sin(0.3) * (t - w * w * t * t * t / 6) + std::cos(0.3) * w * t * t / 2;
      const auto col = static_cast<Eigen::Index>(k);
      CHECK(std::abs(r.trajectory.u(0, col) - u) <= 16 * kEps * std::abs(u));
      CHECK(std::abs(r.trajectory.u(1, col) - u) <= 16 * kEps * std::abs(u));
    }
  }
  // Phase 0, u' = 1e10 sin(1e-10 t) ≈ t: u = t²/2 (to 1e-20 relative). With the π/2-shifted phase
  // the rows moved in steps of 2e-5 and the run failed ('too many steps between two outputs').
  const SceneSpec spec = parse_scene_text(R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 2.0]]
stiffness = [[3.0, -1.0], [-1.0, 1.0]]
[[constraint]]
name = "drive"
level = "velocity"
terms = { a = 1.0 }
value = { type = "harmonic", amplitude = 1e10, omega = 1e-10 }
[solve]
t_end = 10.0
output_step = 1.0
rtol = 1e-10
atol = 1e-12
)",
                                          "slow_ramp.toml");
  const SolveResult ramp = test::solved(build_model(spec), spec.solve);
  REQUIRE(ramp.ok());
  for (std::size_t k = 0; k < ramp.trajectory.t.size(); ++k) {
    const double t = ramp.trajectory.t[k];
    CHECK(std::abs(ramp.trajectory.u(0, static_cast<Eigen::Index>(k)) - t * t / 2) <=
          16 * kEps * t * t / 2);
  }
}

TEST_CASE("elimination of a nearly massless DOF, and auto's fallback when it is singular") {
  // A chain wall - u1 - u2 - u3 with masses 2, m, 1 and springs of 200, u1 fixed: m = 1e-14 is
  // a sound mass (the model's own check warns only beyond a spread of 1/eps); at m = 1e-20 the
  // reduced mass matrix is singular to roundoff, which elimination refuses and GGL integrates.
  const auto scene = [](const std::string& m, const std::string& scheme) {
    return parse_scene_text(R"([model]
type = "matrix"
dofs = ["u1", "u2", "u3"]
mass = [[2.0, 0.0, 0.0], [0.0, )" +
                                m + R"(, 0.0], [0.0, 0.0, 1.0]]
stiffness = [[400.0, -200.0, 0.0], [-200.0, 400.0, -200.0], [0.0, -200.0, 200.0]]
[[load]]
dof = "u3"
value = 10.0
[[constraint]]
terms = { u1 = 1.0 }
[solve]
scheme = ")" + scheme + R"("
t_end = 1.0
output_step = 0.25
rtol = 1e-8
atol = 1e-10
)",
                            "chain.toml");
  };
  const SceneSpec tiny = scene("1e-14", "elimination");
  const Model model = build_model(tiny);
  const SolveResult eliminated = test::solved(model, tiny.solve);
  const SolveResult ggl = test::solved(model, test::under(tiny.solve, Scheme::ggl));
  // Two runs at rtol 1e-8 of a 0.2 m motion: global errors of a few 1e-8, 1e-6 bounds them.
  CHECK((eliminated.trajectory.u - ggl.trajectory.u).cwiseAbs().maxCoeff() < 1e-6);

  const SceneSpec singular = scene("1e-20", "elimination");
  const Model model20 = build_model(singular);
  CHECK_THROWS_AS((void)solve(model20, singular.solve), SchemeNotApplicable);
  const SolveResult automatic =
      test::solved(model20, test::under(singular.solve, Scheme::automatic));
  CHECK(automatic.scheme == Scheme::ggl);
  CHECK(automatic.summary.notes_text().find("auto: elimination refused") != std::string::npos);
  CHECK((automatic.trajectory.u - eliminated.trajectory.u).cwiseAbs().maxCoeff() < 1e-6);
}

TEST_CASE("elimination's reactions do not depend on the scale of a constraint row") {
  // f_con = −Aᵀλ is the same for a row a·u = 0 and (s a)·u = 0; λ scales by 1/s. With s = 1e155
  // A Aᵀ overflowed in the multiplier recovery and elimination reported zero reactions.
  const auto run = [](const std::string& coefficient) {
    const SceneSpec spec = parse_scene_text(test::kTwoMassChainModel + R"([[load]]
dof = "u2"
value = 10.0
[[constraint]]
name = "fix"
terms = { u1 = )" + coefficient + R"( }
[solve]
scheme = "elimination"
t_end = 1.0
output_step = 0.25
)",
                                            "scaled.toml");
    return test::solved(build_model(spec), spec.solve);
  };
  const SolveResult unit = run("1.0"), huge = run("1e155");
  const double scale = unit.trajectory.reaction.cwiseAbs().maxCoeff();
  REQUIRE(scale > 1.0);
  // The same integration (the row enters it only through T and G, exact for a support); the
  // recovery differs by a few roundings of O(scale) values: 64 eps relative.
  CHECK((huge.trajectory.reaction - unit.trajectory.reaction).cwiseAbs().maxCoeff() <=
        64 * kEps * scale);
  CHECK((huge.trajectory.multiplier * 1e155 - unit.trajectory.multiplier).cwiseAbs().maxCoeff() <=
        64 * kEps * scale);
}

TEST_CASE("elimination keeps a tie written at 1e-150 beside a row at 1") {
  // The slave block [[1e-150, 0], [0, 1]] (the tie's slave b, the other row's slave d): LU on it
  // unscaled took 1e-150 for a zero pivot and its solve set u_b to 0 at every time, the tie
  // broken without a word (its drift, in the row's units, read 1e-151). Solved on the rows
  // normalised, u_b − u_c = 0.1 sin 2t holds to roundoff.
  const std::string scene = test::kScaledTieScene + "scheme = \"elimination\"\n";
  const auto s = test::built(parse_scene_text(scene, "tie.toml"));
  const Trajectory& traj = test::solved(s.model, s.spec.solve).trajectory;
  const int b = s.model.dof_at("b"), c = s.model.dof_at("c");
  for (std::size_t k = 0; k < traj.t.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    CAPTURE(traj.t[k]);
    CHECK(std::abs(traj.u(b, col) - traj.u(c, col) - 0.1 * std::sin(2.0 * traj.t[k])) <= 1e-15);
  }
  CHECK(std::abs(traj.u(b, traj.u.cols() - 1)) > 0.05);  // b moves (0.122 at t = 0.8)
}

TEST_CASE("elimination: a named slave that makes the reduction singular is said to be the cause") {
  // a + 1e-11 b = 0 with b the named slave: b = −1e11 a, and the reduced mass 1 + 2e22 of a
  // leaves M̂ singular to roundoff. The automatic choice (a, the larger coefficient) runs.
  const std::string text = R"([model]
type = "matrix"
dofs = ["a", "b", "c"]
mass = [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]]
stiffness = [[4.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]]
[[load]]
dof = "c"
value = 1.0
[[constraint]]
terms = { a = 1.0, b = 1e-11 }
[solve]
t_end = 2.0
output_step = 0.5
scheme = "elimination"
slaves = ["b"]
)";
  const SceneSpec named = parse_scene_text(text, "s.toml");
  CHECK_THROWS_WITH_AS(
      (void)solve(build_model(named), named.solve),
      doctest::Contains("singular to roundoff: elimination needs inertia on every "
                        "motion of the master DOFs that their stiffness does not "
                        "hold; the multiplier schemes (ggl, index1) integrate such "
                        "a model. The slaves are those of [solve] slaves"),
      SchemeNotApplicable);
  SceneSpec automatic = named;
  automatic.solve.slaves.clear();
  automatic.solve.slaves_lines.clear();
  CHECK(test::solved(build_model(automatic), automatic.solve).ok());
}

}  // namespace test_elimination
