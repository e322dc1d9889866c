// IDA's index1 and GGL Newton systems of a linear model solved condensed to [u; λ (; μ)]
// (dae/linsolve/condensed_newton.hpp) against a sparse LU of the full Jacobian J = ∂F/∂y + cj
// ∂F/∂y'.

#include <doctest/doctest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <string>

#include "dae/formulations/multiplier_dae.hpp"
#include "dae/linsolve/condensed_newton.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_condensed_newton {

namespace {

/// A state (y, y') to linearise at and a right-hand side b, smooth and nonzero in every entry.
struct Probe {
  Eigen::VectorXd y, yp, b;
};
Probe probe(int n) {
  Probe p{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) {
    p.y[i] = 0.1 * std::sin(1.3 * i + 0.4);
    p.yp[i] = 0.2 * std::cos(0.9 * i);
    p.b[i] = std::cos(0.7 * i) - 0.3;
  }
  return p;
}

}  // namespace

TEST_CASE("the condensed Newton solve equals the full Jacobian's, index1 and GGL") {
  for (const char* scene : {"chapter_5_5_1", "chapter_5_5_3", "chapter_5_6_1", "chapter_5_6_2"}) {
    const auto built = test::built(
        parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/validation/scenes/" + scene + ".toml"));
    for (const Scheme scheme : {Scheme::index1, Scheme::ggl}) {
      CAPTURE(scene);
      CAPTURE(to_string(scheme));
      const MultiplierDae dae(*built.model.system, scheme, 0.0, 0.0, true);
      const auto newton = dae.newton_system();
      REQUIRE(newton != nullptr);
      const auto [y, yp, b] = probe(dae.size());
      for (const double cj : {1e2, 1e5}) {
        CAPTURE(cj);
        Eigen::SparseMatrix<double> J = dae.jacobian_pattern().matrix();
        dae.jacobian(0.5, y, yp, cj, J);
        Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(J);
        REQUIRE(lu.info() == Eigen::Success);
        const Eigen::VectorXd expected = lu.solve(b);
        REQUIRE(newton->setup(cj));
        Eigen::VectorXd x = b;
        newton->solve(x);
        const Eigen::VectorXd residual = J * x - b;
        // Both are backward stable solves of J x = b: the residual is roundoff of |J| |x|.
        CHECK(residual.norm() <= 1e-10 * (1.0 + J.norm() * x.norm()));
        CHECK((x - expected).norm() <= 1e-6 * (1.0 + expected.norm()));
      }
    }
  }
}

TEST_CASE("the condensed saddle point keeps its pivots as cj moves: multipliers scaled to S") {
  // The 20 x 20 lattice (unit masses and EA, its left column held) with two ties. Unscaled, the
  // multipliers' pivots of [S, Aᵀ; A, 0] came out about 1/cj² against S's cj² (S = K + cj C +
  // cj² M): with these unit masses, from cj about 1e5 on KLU's rcond test rejected the
  // refactorizations and each setup pivoted afresh (6 of the 8 here).
  const std::string ties =
      "[[constraint]]\nname = \"tie1\"\nterms = { uy400 = 1.0, uy20 = -1.0 }\n"
      "[[constraint]]\nname = \"tie2\"\nterms = { ux390 = 1.0, ux10 = -1.0 }\n";
  const auto built = test::built(parse_scene_text(test::lattice(20, 20, ties, ""), "l.toml"));
  for (const Scheme scheme : {Scheme::index1, Scheme::ggl}) {
    CAPTURE(to_string(scheme));
    const MultiplierDae dae(*built.model.system, scheme, 0.0, 0.0, true);
    const auto newton = dae.newton_system();
    const auto* condensed = dynamic_cast<const CondensedNewton*>(newton.get());
    REQUIRE(condensed != nullptr);
    const auto [y, yp, b] = probe(dae.size());
    // cj as IDA moves it: up from a start and down again, by factors up to 3.
    for (const double cj : {1e4, 3e4, 4e4, 1.2e5, 3e5, 1e6, 5e5, 2e5}) {
      CAPTURE(cj);
      Eigen::SparseMatrix<double> J = dae.jacobian_pattern().matrix();
      dae.jacobian(0.5, y, yp, cj, J);
      REQUIRE(newton->setup(cj));
      Eigen::VectorXd x = b;
      newton->solve(x);
      CHECK((J * x - b).norm() <= 1e-10 * (1.0 + J.norm() * x.norm()));
    }
    CHECK(condensed->pivoting_factorizations() == 1);
  }
}

TEST_CASE("a condensed system whose constraint rows store no entry is singular, not a crash") {
  // Two DOFs with unit mass and stiffness and one row of A that stores nothing: no scale can be
  // taken from A, and [S, 0; 0, 0] is singular, which setup reports.
  LinearMatrices matrices;
  matrices.M = Eigen::MatrixXd::Identity(2, 2).sparseView();
  matrices.K = matrices.M;
  matrices.A.resize(1, 2);
  CondensedNewton newton(Scheme::index1, std::move(matrices), Eigen::SparseMatrix<double>(0, 1));
  CHECK_FALSE(newton.setup(10.0));
}

TEST_CASE("[solve] newton = \"condensed\" runs agree with the full Jacobian's, damping included") {
  // A 20 x 20 tied lattice with Rayleigh damping: index1, GGL and elimination, each solved with
  // the full Jacobian (default) and condensed; the same solution to the tolerance's size.
  std::string ties;
  for (int i = 5; i < 20; i += 5) {
    ties += "[[constraint]]\nname = \"tie" + std::to_string(i) + "\"\nterms = { uy" +
            std::to_string(19 * 20 + i + 1) + " = 1.0, uy" + std::to_string(i + 1) + " = -1.0 }\n";
  }
  ties += "[[load]]\ndof = \"uy400\"\nvalue = { type = \"step\", amplitude = -1.0 }\n";
  std::string text = test::lattice(20, 20, ties, "rtol = 1e-8\natol = 1e-10\n");
  text.replace(text.find("supports = "), 0, "damping = { rayleigh = [0.1, 0.01] }\n");
  const auto full = test::built(parse_scene_text(text, "lattice.toml"));
  SolveSpec condensed_settings = full.spec.solve;
  condensed_settings.condensed_newton = true;
  for (const Scheme scheme : {Scheme::index1, Scheme::ggl, Scheme::elimination}) {
    CAPTURE(to_string(scheme));
    const SolveResult a = test::solved(full.model, test::under(full.spec.solve, scheme));
    const SolveResult b = test::solved(full.model, test::under(condensed_settings, scheme));
    const double scale = a.trajectory.u.cwiseAbs().maxCoeff();
    REQUIRE(scale > 0.0);
    // Two runs at rtol 1e-8 of the same equations: 100 rtol of the largest displacement.
    CHECK((a.trajectory.u - b.trajectory.u).cwiseAbs().maxCoeff() <= 100 * 1e-8 * scale);
    CHECK(b.summary.jacobian_nonzeros < a.summary.jacobian_nonzeros);  // the smaller matrix
  }
}

TEST_CASE("[solve] newton accepts full or condensed only") {
  const std::string scene =
      "[model]\ntype = \"matrix\"\ndofs = [\"x\"]\nmass = [[1.0]]\n"
      "stiffness = [[1.0]]\n[solve]\nt_end = 1.0\noutput_step = 0.5\n";
  CHECK_FALSE(parse_scene_text(scene, "s.toml").solve.condensed_newton);  // default full
  CHECK(parse_scene_text(scene + "newton = \"condensed\"\n", "s.toml").solve.condensed_newton);
  CHECK_THROWS_WITH_AS((void)parse_scene_text(scene + "newton = \"sparse\"\n", "s.toml"),
                       doctest::Contains("solve.newton: expected 'full' or 'condensed'"),
                       SceneError);
}

TEST_CASE("KLU with kept pivots: refactorizations, and a new pivot order when they fail") {
  // The first matrix pivots on its diagonal; the second has a zero where that pivot was, so
  // its refactorization with the old pivots cannot stand and a pivoting factorization follows.
  Eigen::SparseMatrix<double> A(3, 3);
  A.insert(0, 0) = 4.0;
  A.insert(0, 1) = 1.0;
  A.insert(1, 0) = 1.0;
  A.insert(1, 1) = 3.0;
  A.insert(1, 2) = 1.0;
  A.insert(2, 1) = 1.0;
  A.insert(2, 2) = 2.0;
  A.makeCompressed();
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, -2.0, 0.5);
  FixedPatternKlu klu;
  REQUIRE(klu.factor(A));
  CHECK((A * klu.solve(b) - b).norm() <= 1e-14);
  A.coeffRef(0, 0) = 5.0;  // same pivots do
  REQUIRE(klu.factor(A));
  CHECK((A * klu.solve(b) - b).norm() <= 1e-14);
  CHECK(klu.pivoting_factorizations() == 1);
  CHECK(klu.refactorizations() == 1);
  A.coeffRef(0, 0) = 0.0;  // the kept first pivot is zero: pivot again
  REQUIRE(klu.factor(A));
  Eigen::VectorXd x = b;
  klu.solve_in_place(x);
  CHECK((A * x - b).norm() <= 1e-14);
  CHECK(klu.pivoting_factorizations() == 2);
  Eigen::SparseMatrix<double> singular = A;
  singular.coeffRef(0, 1) = 0.0;  // column 0 all zero
  singular.coeffRef(1, 0) = 0.0;
  CHECK_FALSE(klu.factor(singular));
}

}  // namespace test_condensed_newton
