// The elimination path at real size (issue 12): the master-slave transform built group by group
// (models/core/master_slave.hpp), sparse T and G, sparse reduced loads, and a 20,000-DOF
// lattice that runs under elimination as under index1.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "dae/formulations/constraint_treatment.hpp"
#include "dae/formulations/reduced_system.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"
#include "tests/sparse_elimination_scene.hpp"

using namespace condyn;

namespace test_sparse_elimination {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

}  // namespace

TEST_CASE("sparse master-slave transform: A T = 0 and A G = I, nonzeros only inside the groups") {
  const Model model = build_model(parse_scene_text(test::tied_lattice(""), "lattice.toml"));
  const int n = model.dofs(), m = model.constraint_count();
  REQUIRE(n == 20000);
  REQUIRE(m == 200 + 9);  // the left column's supports (x and y of 100 nodes) and the ties
  const MasterSlave ms = master_slave_transform(model.A);
  CHECK(ms.T.rows() == n);
  CHECK(ms.T.cols() == n - m);
  // A T = 0 and A G = I up to the roundoff of one solve with the slave block (coefficients 1:
  // a few eps).
  const Eigen::SparseMatrix<double> AT = model.A * ms.T;
  const Eigen::SparseMatrix<double> AG = model.A * ms.G;
  double worst_at = 0.0, worst_ag = 0.0;
  for (int k = 0; k < AT.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(AT, k); it; ++it)
      worst_at = std::max(worst_at, std::abs(it.value()));
  const Eigen::MatrixXd ag(AG);
  worst_ag = (ag - Eigen::MatrixXd::Identity(m, m)).cwiseAbs().maxCoeff();
  CHECK(worst_at <= 4 * kEps);
  CHECK(worst_ag <= 4 * kEps);
  // Supports are 1 x 1 groups (their slave rows of T are empty), each tie a 1 x 2 group (one
  // entry): nnz(T) = masters + ties, linear in n, where the dense transform held n x (n - m).
  CHECK(ms.T.nonZeros() == (n - m) + 9);
  CHECK(ms.G.nonZeros() == m);
}

TEST_CASE("elimination declines a coupled group beyond its dense block, naming the constraint") {
  // A chain of 2,100 rows over 2,101 DOFs of one row of nodes, u_(k+1) = u_k, joined by the
  // support of node 1 (fix_ux1): one coupled group of 2,101 rows, 4.4e6 entries, beyond
  // kMaxDenseGroupEntries.
  std::string chain;
  for (int k = 1; k <= 2100; ++k) {
    chain += "[[constraint]]\nname = \"link" + std::to_string(k) + "\"\nterms = { ux" +
             std::to_string(k + 1) + " = 1.0, ux" + std::to_string(k) + " = -1.0 }\n";
  }
  const auto scene = test::built(parse_scene_text(test::lattice(2200, 1, chain, ""), "chain.toml"));
  CHECK_THROWS_WITH_AS((void)reduce(scene.model),
                       doctest::Contains("elimination: constraint 'fix_ux1' and 2100 others: "
                                         "2101 constraints coupled through shared DOFs over "
                                         "2101 DOFs"),
                       SchemeNotApplicable);  // bad input for the CLI (exit 2), not a failure
  // One row over 2,101 DOFs (their mean is 0): few rows, but its elimination would couple 2,100
  // masters densely (4.4e6 entries in the reduced matrices).
  std::string mean = "[[constraint]]\nname = \"mean\"\nterms = { ";
  for (int k = 2; k <= 2102; ++k) mean += (k > 2 ? ", uy" : "uy") + std::to_string(k) + " = 1.0";
  mean += " }\n";
  const auto wide = test::built(parse_scene_text(test::lattice(2200, 1, mean, ""), "mean.toml"));
  CHECK_THROWS_WITH_AS(
      (void)reduce(wide.model),
      doctest::Contains("elimination: constraint 'mean': 1 constraint(s) over 2101 "
                        "DOFs; eliminating their slaves couples the 2100 masters"),
      std::invalid_argument);
  // The mixed treatment keeps that row as a multiplier (it threw while building the transform).
  const ConstraintTreatment mixed = treat_constraints(wide.model);
  const int mean_row = wide.model.constraint_count() - 1;
  CHECK(wide.model.constraints.back().name == "mean");
  CHECK(mixed.reason[static_cast<std::size_t>(mean_row)] ==
        ConstraintTreatment::Reason::group_too_large);
  CHECK(mixed.kept == std::vector<int>{mean_row});
}

TEST_CASE("the mixed treatment tries no group whose dense work exceeds its bound") {
  // Two chains of ties along a row of 500 nodes (node 1 supported apart): ux_(k+1) = ux_k over
  // nodes 2 to 52 (50 rows over 51 DOFs, 50² x 51 = 1.3e5 within the trial's bound of 1e8; a
  // group near the bound costs its trial, a minute under the sanitizers) and uy_(k+1) = uy_k
  // over nodes 2 to 482 (480 rows over 481 DOFs, 1.1e8 just beyond it). Both are
  // within the dense block's limits (2.3e5 entries), and each stays sparse (every slave equals
  // the one master). The mixed treatment eliminates the first and keeps the second's
  // multipliers untried (its QR, LU and condition number grow like rows² x DOFs: seconds for the
  // joint rows of a chain of 1,000 bodies); elimination, named, still eliminates both.
  std::string ties;
  const auto tie = [&ties](const char* axis, int k) {
    ties += std::string("[[constraint]]\nname = \"") + axis + std::to_string(k) + "\"\nterms = { " +
            axis + std::to_string(k + 1) + " = 1.0, " + axis + std::to_string(k) + " = -1.0 }\n";
  };
  for (int k = 2; k <= 51; ++k) tie("ux", k);
  for (int k = 2; k <= 481; ++k) tie("uy", k);
  const auto scene = test::built(parse_scene_text(test::lattice(500, 1, ties, ""), "ties.toml"));
  const ConstraintTreatment t = treat_constraints(scene.model);
  REQUIRE(scene.model.constraint_count() == 2 + 50 + 480);  // node 1's support, then the ties
  const auto reason = [&t](int row) { return t.reason[static_cast<std::size_t>(row)]; };
  for (int row = 2; row < 52; ++row)
    CHECK(reason(row) == ConstraintTreatment::Reason::sparse_group);
  for (int row = 52; row < 532; ++row)
    CHECK(reason(row) == ConstraintTreatment::Reason::group_too_large);
  CHECK(t.kept.size() == 480);
  CHECK(treatment_report(scene.model, t)
            .find("480 multipliers (coupled group too large for the "
                  "dense transform)") != std::string::npos);
  CHECK(reduce(scene.model).transform.slaves.size() == 532);
}

TEST_CASE("auto picks elimination or GGL by the size of the Newton matrix each factors") {
  // The tied lattice (20 x 20 nodes: the choice does not depend on its size, and the sanitized
  // build took 15 s over the 100 x 100 one): supports and two-DOF ties leave T as sparse as A;
  // elimination factors the smaller matrix. By default (mixed treatment) each group is found to
  // stay sparse; with every row kept as a multiplier ([solve] constraints = "multipliers"), auto
  // compares the Newton matrices of elimination and GGL.
  const auto lattice = test::built(parse_scene_text(test::tied_lattice("", 20), "lattice.toml"));
  const SchemeChoice tied = choose_scheme(lattice.model, lattice.spec.solve);
  CHECK(tied.scheme == Scheme::elimination);
  CHECK(tied.reason.find("its elimination stays sparse") != std::string::npos);
  SolveSpec pure = lattice.spec.solve;
  pure.treatment = SolveSpec::Treatment::multipliers;
  const SchemeChoice tied_pure = choose_scheme(lattice.model, pure);
  CHECK(tied_pure.scheme == Scheme::elimination);
  CHECK(tied_pure.reason.find("elimination solves the smaller system") != std::string::npos);
  // A chain of 100 DOFs whose mean is held: one row over every DOF. Its slave's row of T has 99
  // entries, so T^T K T couples every master with every other (about 99^2 nonzeros) where GGL's
  // matrix keeps the chain's few hundred: GGL.
  std::string rows, mass, terms;
  const int n = 100;
  for (int i = 0; i < n; ++i) {
    std::string row;
    for (int j = 0; j < n; ++j) {
      const double k = i == j ? 2.0 : (std::abs(i - j) == 1 ? -1.0 : 0.0);
      row += (j ? ", " : "") + std::to_string(k);
    }
    rows += std::string(i ? ", " : "") + "[" + row + "]";
    terms += std::string(i ? ", " : "") + "u" + std::to_string(i + 1) + " = 1.0";
  }
  std::string dofs, diag;
  for (int i = 1; i <= n; ++i)
    dofs += std::string(i > 1 ? ", " : "") + "\"u" + std::to_string(i) + "\"";
  for (int i = 0; i < n; ++i) {
    std::string row;
    for (int j = 0; j < n; ++j) row += std::string(j ? ", " : "") + (i == j ? "1.0" : "0.0");
    diag += std::string(i ? ", " : "") + "[" + row + "]";
  }
  const auto chain = test::built(parse_scene_text(
      "[model]\ntype = \"matrix\"\ndofs = [" + dofs + "]\nmass = [" + diag + "]\nstiffness = [" +
          rows + "]\n[[constraint]]\nname = \"mean\"\nterms = { " + terms +
          " }\n[solve]\nt_end = 1.0\noutput_step = 0.1\n",
      "chain.toml"));
  const SchemeChoice filled = choose_scheme(chain.model, chain.spec.solve);
  CHECK(filled.scheme == Scheme::ggl);
  CHECK(filled.reason.find("0 rows eliminated, 1 kept as multipliers") != std::string::npos);
  pure = chain.spec.solve;
  pure.treatment = SolveSpec::Treatment::multipliers;
  const SchemeChoice filled_pure = choose_scheme(chain.model, pure);
  CHECK(filled_pure.scheme == Scheme::ggl);
  CHECK(filled_pure.reason.find("the master-slave transform fills in") != std::string::npos);
  // A request is taken as it is.
  CHECK(choose_scheme(chain.model, test::under(chain.spec.solve, Scheme::elimination)).scheme ==
        Scheme::elimination);
}

}  // namespace test_sparse_elimination
