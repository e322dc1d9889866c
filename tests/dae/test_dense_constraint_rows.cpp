// A constraint over many DOFs (a floor's average drift held at zero): the saddle-point
// factorizations keep it sparse (dae/linsolve/kkt.hpp's KktLu), penalty, whose spring would couple
// every DOF of the row, refuses it up front, and the other schemes run it.

#include <doctest/doctest.h>

#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "dae/linsolve/kkt.hpp"
#include "dae/run/solve.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_dense_constraint_rows {

namespace {

/// A 50 x 25 lattice (2,500 DOFs, its left column supported) with one row: the average of the
/// first `terms` free displacements (ux then uy, node by node) held at zero; a step load pulls
/// the far corner down.
std::string averaged_lattice(int terms) {
  std::string row = "[[constraint]]\nname = \"average\"\nterms = { ";
  int written = 0;
  for (int node = 1; node <= 50 * 25 && written < terms; ++node) {
    if ((node - 1) % 50 == 0) continue;  // supported
    for (const char* axis : {"ux", "uy"}) {
      if (written == terms) break;
      row += std::string(written ? ", " : "") + axis + std::to_string(node) + " = 1.0";
      ++written;
    }
  }
  row += " }\n[[load]]\ndof = \"uy1250\"\nvalue = { type = \"step\", amplitude = -1.0 }\n";
  return test::lattice(50, 25, row, "");
}

}  // namespace

TEST_CASE("KktLu: a dense constraint row leaves the saddle point's factors sparse") {
  // M diagonal (n = 3,000), one row over every DOF and 749 ties of two DOFs each: [M Aᵀ; A 0].
  const int n = 3000;
  Eigen::SparseMatrix<double> M(n, n), A(n / 4, n);
  for (int i = 0; i < n; ++i) M.insert(i, i) = 1.0 + i % 7;
  for (int i = 0; i < n; ++i) A.insert(0, i) = 1.0;
  for (Eigen::Index k = 1; k < n / 4; ++k) {
    A.insert(k, 4 * k) = 1.0;
    A.insert(k, 4 * k + 2) = -1.0;
  }
  M.makeCompressed();
  A.makeCompressed();
  const Eigen::SparseMatrix<double> kkt = kkt_matrix(M, A);
  const KktLu lu(kkt);
  REQUIRE(lu.info() == Eigen::Success);
  // The factors stay near the matrix's own 11,996 nonzeros (17,245 entries). Eigen's SparseLU,
  // which these factorizations used before, gave 578,246 under AMD (48 times; under COLAMD
  // 17,994 here, but 2.5·10⁷ on the benchmark lattice with such a row).
  CHECK(lu.factor_entries() < 2 * kkt.nonZeros());
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(kkt.rows(), -1.0, 1.0);
  const Eigen::VectorXd x = lu.solve(rhs);
  CHECK((kkt * x - rhs).lpNorm<Eigen::Infinity>() <
        1e-13 * (1.0 + x.lpNorm<Eigen::Infinity>()) * n);
  // A singular matrix: two rows the same (dependent constraints).
  Eigen::SparseMatrix<double> twice(2, n);
  twice.insert(0, 5) = 1.0;
  twice.insert(1, 5) = 1.0;
  twice.makeCompressed();
  CHECK(KktLu(kkt_matrix(M, twice)).info() == Eigen::NumericalIssue);
}

TEST_CASE("penalty refuses a row whose spring would be a dense block and the others run it") {
  // 2,450 terms: a block of 6.0e6 entries, beyond elimination's and penalty's 4e6.
  const auto wide = test::built(parse_scene_text(averaged_lattice(2450), "wide.toml"));
  const auto why = scheme_refusal(wide.model, Scheme::penalty);
  REQUIRE(why.has_value());
  CHECK(why->find("constraint 'average' has 2450 terms; its spring couples them all, a dense "
                  "block of 6.0025e+06 entries") != std::string::npos);
  CHECK(why->find("use index1, ggl or auto") != std::string::npos);
  for (Scheme s : {Scheme::index1, Scheme::ggl, Scheme::projection}) {
    CHECK_FALSE(scheme_refusal(wide.model, s).has_value());
  }
  // GGL and projection agree on the tip's motion; the row holds.
  const SolveResult ggl = test::solved(wide.model, test::under(wide.spec.solve, Scheme::ggl));
  const SolveResult projection =
      test::solved(wide.model, test::under(wide.spec.solve, Scheme::projection));
  const Eigen::Index tip = wide.model.dof_at("uy1250");
  const double scale = ggl.trajectory.u.row(tip).cwiseAbs().maxCoeff();
  REQUIRE(scale > 0.0);
  CHECK((ggl.trajectory.u.row(tip) - projection.trajectory.u.row(tip)).cwiseAbs().maxCoeff() <
        1e-3 * scale);
  CHECK(ggl.trajectory.drift_position.maxCoeff() < 1e-10);

  // 1,000 terms (1e6 entries): penalty runs it.
  const auto narrow = test::built(parse_scene_text(averaged_lattice(1000), "narrow.toml"));
  CHECK_FALSE(scheme_refusal(narrow.model, Scheme::penalty).has_value());
}

}  // namespace test_dense_constraint_rows
