// The natural modes (models/core/pencil_modes.hpp, natural_modes.hpp): the dense path and
// shift-invert Lanczos against the closed form of a uniform shear building (tests/
// shear_building.hpp) and against an independent dense solution on the constraints' null space;
// massless DOFs condensed; participating mass ratios; the refusals.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "dae/formulations/natural_modes.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/null_space.hpp"
#include "models/core/pencil_modes.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/shear_building.hpp"
#include "validation/studies/scene_modes.hpp"

using namespace condyn;

namespace test_natural_modes {

using condyn::test::ShearBuilding;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The dense generalized solver is backward stable: each ω² is off by a few eps times the
// pencil's scale, ω²_max <= 4 k/m for the shear building; 64 eps of it (observed 8.3 eps on
// 10 storeys).
constexpr double kDenseRoundoff = 64 * kEps;
// Lanczos: Ritz values to kModeTolerance relative (Spectra's test on |ν| of the shifted
// pencil), 10 of it for the eigenvalue; plus the factorization's backward error, which moves each
// ω² by about eps times ω²_max, taken as the dense path's bound (observed 5.3e-15 relative on the
// 12 lowest ω² of 500 storeys, where ω²_max / ω²_1 is 1e6; residuals 8.8e-12 relative).
constexpr double kLanczosTolerance = 10 * kModeTolerance;

Model model_of(const std::string& text) { return build_model(parse_scene_text(text, "m.toml")); }

/// |ω² − ω²_exact| within the tolerance of the path: relative `rel` plus 64 eps ω²_max.
void check_omega(double omega, double exact, double omega2_max, double rel) {
  const double bound = rel * exact * exact + kDenseRoundoff * omega2_max;
  CHECK(std::abs(omega * omega - exact * exact) <= bound);
}

/// K (tridiagonal) and M (m I) of the shear building as sparse matrices, n storeys.
void shear_pencil(int n, double m, double k, Eigen::SparseMatrix<double>& K,
                  Eigen::SparseMatrix<double>& M) {
  std::vector<Eigen::Triplet<double>> kt, mt;
  for (int i = 0; i < n; ++i) {
    kt.emplace_back(i, i, i + 1 < n ? 2.0 * k : k);
    if (i + 1 < n) {
      kt.emplace_back(i, i + 1, -k);
      kt.emplace_back(i + 1, i, -k);
    }
    mt.emplace_back(i, i, m);
  }
  K.resize(n, n);
  M.resize(n, n);
  K.setFromTriplets(kt.begin(), kt.end());
  M.setFromTriplets(mt.begin(), mt.end());
}

}  // namespace

TEST_CASE("modes: a uniform shear building against its closed form, dense and Lanczos") {
  for (const int n : {1, 10}) {
    ShearBuilding b{.storeys = n, .mass = 2.0, .stiffness = 800.0};
    const Model model = model_of(test::shear_building_scene(b));
    const NaturalModes modes = natural_modes(model, n);
    CHECK(modes.dense);
    CHECK(modes.available == n);
    for (int j = 1; j <= n; ++j)
      check_omega(modes.omega[j - 1], test::shear_building_omega(b, j), 4 * 800.0 / 2.0, 0.0);
  }
  // 500 storeys by Lanczos (the automatic choice above kDenseModeDofs), its lowest 12; 12,000
  // storeys, where the shift-invert factorization is CHOLMOD's (above kCholmodAbove).
  for (const int n : {500, 12000}) {
    CAPTURE(n);
    const ShearBuilding b{.storeys = n, .mass = 3.0, .stiffness = 1.2e4};
    Eigen::SparseMatrix<double> K, M;
    shear_pencil(n, b.mass, b.stiffness, K, M);
    const PencilModes modes = lowest_modes(K, M, 12);
    CHECK_FALSE(modes.dense);
    for (int j = 1; j <= 12; ++j) {
      check_omega(std::sqrt(modes.omega2[j - 1]), test::shear_building_omega(b, j),
                  4 * b.stiffness / b.mass, kLanczosTolerance);
    }
    // Each shape solves the pencil: ‖Kφ − ω²Mφ‖ small against ‖Kφ‖ + ω²‖Mφ‖, plus the roundoff
    // of forming the residual, 64 eps (‖|K||φ|‖ + ω²‖|M||φ|‖): for the lowest modes of 12,000
    // storeys (ω²_1 / ω²_max ≈ 4e-9) that roundoff, not Lanczos, is the larger (observed
    // 1.3e-12 against 2.4e-13 for the first term).
    const Eigen::SparseMatrix<double> abs_k = K.cwiseAbs(), abs_m = M.cwiseAbs();
    for (int j = 0; j < 12; ++j) {
      const Eigen::VectorXd phi = modes.shapes.col(j);
      const Eigen::VectorXd r = K * phi - modes.omega2[j] * (M * phi);
      const Eigen::VectorXd abs_phi = phi.cwiseAbs();
      CHECK(r.norm() <=
            kLanczosTolerance * ((K * phi).norm() + modes.omega2[j] * (M * phi).norm()) +
                kDenseRoundoff *
                    ((abs_k * abs_phi).norm() + modes.omega2[j] * (abs_m * abs_phi).norm()));
      CHECK(phi.dot(M * phi) == doctest::Approx(1.0).epsilon(kDenseRoundoff * n));
    }
  }
}

TEST_CASE("modes: a free chain's rigid motion by Lanczos, through the negative shift") {
  // n masses m joined by n − 1 springs k, nothing holding them: K is singular, so Lanczos factors
  // K + sM instead of K. ω_j = 2 sqrt(k/m) sin((j − 1) π / (2n)) (the shear building's argument
  // with φ_i = cos((i − ½) θ), free at both ends); ω_1 = 0, the rigid translation. Observed:
  // ω²_1 clamped to 0, 3.4e-12 relative on the others, the rigid shape to 3e-15.
  // 500 masses, and 12,000 where the factorization is CHOLMOD's (its Cholesky of the singular K
  // meets a pivot at roundoff or not positive: either way the shift is taken).
  const double m = 2.0, k = 5.0e3, pi = 3.14159265358979323846;
  for (const int n : {500, 12000}) {
    CAPTURE(n);
    Eigen::SparseMatrix<double> K, M;
    shear_pencil(n, m, k, K, M);
    K.coeffRef(0, 0) = k;  // the first mass's spring to the ground removed
    const PencilModes modes = lowest_modes(K, M, 6);
    CHECK_FALSE(modes.dense);
    for (int j = 1; j <= 6; ++j) {
      const double exact = 2.0 * std::sqrt(k / m) * std::sin((j - 1) * pi / (2.0 * n));
      check_omega(std::sqrt(modes.omega2[j - 1]), exact, 4 * k / m, kLanczosTolerance);
    }
    // The rigid mode: every mass moves alike, 1/sqrt(n m) each for φᵀMφ = 1.
    const Eigen::VectorXd rigid = modes.shapes.col(0);
    CHECK((rigid.array() - 1.0 / std::sqrt(n * m)).abs().maxCoeff() <= kLanczosTolerance);
  }
}

TEST_CASE("modes: massless DOFs are condensed exactly, on both paths") {
  // Springs of 2k in series through massless DOFs: storey stiffness k, the same closed form.
  const ShearBuilding b{.storeys = 6, .mass = 1.5, .stiffness = 30.0, .massless_midpoints = true};
  const Model model = model_of(test::shear_building_scene(b));
  for (const ModeSolver solver : {ModeSolver::dense, ModeSolver::sparse}) {
    CAPTURE(static_cast<int>(solver));
    const NaturalModes modes = natural_modes(model, 4, solver);
    CHECK(modes.available == 6);
    for (int j = 1; j <= 4; ++j) {
      check_omega(modes.omega[j - 1], test::shear_building_omega(b, j), 4 * 2 * 30.0 / 1.5,
                  solver == ModeSolver::sparse ? kLanczosTolerance : 0.0);
    }
    // A massless DOF sits halfway between its storeys (equal springs): h_i = (u_{i−1} + u_i)/2.
    const Eigen::VectorXd phi = modes.shapes.col(0);
    for (int i = 1; i <= 6; ++i) {
      const double below = i == 1 ? 0.0 : phi[model.dof_at("u" + std::to_string(i - 1))];
      const double mid = phi[model.dof_at("h" + std::to_string(i))];
      CHECK(std::abs(mid - 0.5 * (below + phi[model.dof_at("u" + std::to_string(i))])) <=
            kLanczosTolerance * phi.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("modes: under constraints, both paths against a dense solution on null(A)") {
  // The building with its base as a DOF held by a constraint and two storeys tied (u2 = u4):
  // the reference is independent of the master-slave reduction, an orthonormal basis N of null(A)
  // and Eigen's generalized solver on (NᵀKN, NᵀMN).
  ShearBuilding b{.storeys = 8, .mass = 1.0, .stiffness = 50.0, .base_dof = true};
  std::string text = test::shear_building_scene(b);
  text = test::replace(text, "[solve]",
                       "[[constraint]]\nname = \"tie\"\nterms = { u2 = 1.0, u4 = -1.0 }\n[solve]");
  const Model model = model_of(text);
  const Eigen::MatrixXd N = null_space_basis(model.A, model.dofs());
  const Eigen::MatrixXd Md(model.M), Kd(*model.K);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ref(
      N.transpose() * Kd * N, N.transpose() * Md * N, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  const auto count = static_cast<int>(ref.eigenvalues().size());
  CHECK(count == 7);  // 9 DOFs, 2 constraints
  for (const ModeSolver solver : {ModeSolver::dense, ModeSolver::sparse}) {
    CAPTURE(static_cast<int>(solver));
    const int k = solver == ModeSolver::sparse ? count - 2 : count;  // Lanczos: fewer than all
    const NaturalModes modes = natural_modes(model, k, solver);
    CHECK(modes.available == count);
    const double rel = solver == ModeSolver::sparse ? kLanczosTolerance : 0.0;
    for (int j = 0; j < k; ++j) {
      check_omega(modes.omega[j], std::sqrt(ref.eigenvalues()[j]), 4 * 50.0, rel);
      const Eigen::VectorXd phi = modes.shapes.col(j);
      // A φ = 0 (roundoff of O(1) entries) and the equations hold on null(A): residuals of the
      // path's relative accuracy on entries up to ω²_max = 4 k/m, summed over the 7 coordinates.
      CHECK((model.A * phi).norm() <= kDenseRoundoff);
      const Eigen::VectorXd r =
          N.transpose() * (Kd * phi - modes.omega[j] * modes.omega[j] * (Md * phi));
      CHECK(r.norm() <= (rel + kDenseRoundoff) * 4 * 50.0 * count);
      // The same shape as the reference's, up to sign (distinct frequencies here).
      const Eigen::VectorXd psi = N * ref.eigenvectors().col(j);
      CHECK(std::abs(std::abs(phi.dot(Md * psi)) - 1.0) <=
            (rel + kDenseRoundoff) * 4 * 50.0 * count);
    }
  }
}

TEST_CASE("modes: participating mass ratios sum to 1 over every mode, supports' mass apart") {
  for (const bool midpoints : {false, true}) {
    CAPTURE(midpoints);
    ShearBuilding b{.storeys = 7,
                    .mass = 2.5,
                    .stiffness = 10.0,
                    .base_dof = true,
                    .massless_midpoints = midpoints,
                    .ground_motion = true};
    const Model model = model_of(test::shear_building_scene(b));
    const NaturalModes modes = natural_modes(model, 7);
    // The base's mass is a support's: the total is the storeys', n m (roundoff of n terms).
    CHECK(std::abs(modes.total_mass - 7 * 2.5) <= 64 * kEps * 7 * 2.5);
    CHECK(std::abs(modes.mass_ratio.sum() - 1.0) <= 64 * kEps * 7);
    CHECK(std::abs(modes.mass_ratio_cumulative[6] - 1.0) <= 64 * kEps * 7);
    // The first mode of a uniform shear building carries most of the mass: 86 % for 7 storeys,
    // Γ₁²/(n m) from the closed-form shape φ_i = sin(i θ₁), θ₁ = π/15 (observed exact to the
    // last bit, as the total and the sum above); each ratio in (0, 1).
    for (int j = 0; j < 7; ++j) CHECK((modes.mass_ratio[j] > 0.0 && modes.mass_ratio[j] < 1.0));
    const double pi = 3.14159265358979323846, theta = pi / 15.0;
    double sum = 0.0, squares = 0.0;
    for (int i = 1; i <= 7; ++i) {
      sum += std::sin(i * theta);
      squares += std::sin(i * theta) * std::sin(i * theta);
    }
    CHECK(std::abs(modes.mass_ratio[0] - sum * sum / (squares * 7)) <= 64 * kEps * 7);
  }
}

TEST_CASE("modes: refusals name what is wrong") {
  const ShearBuilding b{.storeys = 3};
  const SceneSpec spec = parse_scene_text(test::shear_building_scene(b), "b.toml");
  const auto message = [&](const SceneSpec& s, std::optional<int> count) {
    try {
      (void)scene_modes(s, count, "--count");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK(message(spec, 0).find("b.toml: --count: must be from 1 to the number of modes of the "
                              "constrained model, 3 (3 DOFs, 0 constraints); got 0") !=
        std::string::npos);
  CHECK(message(spec, 4).find("--count") != std::string::npos);
  CHECK(message(spec, 3) == "accepted");
  CHECK(scene_modes(spec, std::nullopt, "--count").modes.omega.size() == 3);  // default: all 3
  ShearBuilding massless = b;
  massless.mass_scale = 0.0;
  CHECK(message(parse_scene_text(test::shear_building_scene(massless), "b.toml"), 1)
            .find("b.toml: model.mass: the model has no mass") != std::string::npos);
  CHECK(message(
            parse_scene_text(test::pendulum_scene("t_end = 1.0\noutput_step = 0.5\n"), "p.toml"), 1)
            .find("p.toml: model: natural modes need a linear model") != std::string::npos);
  // The pencil's own limits: Lanczos gives fewer than all modes; the dense path every one.
  Eigen::SparseMatrix<double> K, M;
  shear_pencil(5, 1.0, 1.0, K, M);
  CHECK_THROWS_AS((void)lowest_modes(K, M, 4, ModeSolver::sparse), std::invalid_argument);
  CHECK(lowest_modes(K, M, 5, ModeSolver::dense).omega2.size() == 5);
  CHECK_THROWS_AS((void)lowest_modes(K, M, 6), std::invalid_argument);
  // A stiffness that is not positive semi-definite: an unstable model, on both paths.
  const Eigen::SparseMatrix<double> negative = -K;
  CHECK_THROWS_AS((void)lowest_modes(negative, M, 2, ModeSolver::dense), ModesUnavailable);
  CHECK_THROWS_AS((void)lowest_modes(negative, M, 2, ModeSolver::sparse), ModesUnavailable);
}

}  // namespace test_natural_modes
