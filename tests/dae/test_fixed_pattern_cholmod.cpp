// CHOLMOD on symmetric positive-definite Newton matrices (models/core/fixed_pattern_cholmod.hpp,
// dae/run/factorization_choice.hpp): solves against the matrix, the analysis kept across
// factorizations, the least-fill ordering, a matrix not positive definite, elimination and
// penalty runs under KLU and CHOLMOD giving the same results, and the key's refusals.

#include <dlfcn.h>
#include <doctest/doctest.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "dae/interface/scheme_not_applicable.hpp"
#include "dae/run/factorization_choice.hpp"
#include "dae/run/run_plan.hpp"
#include "dae/run/scheme_memory.hpp"
#include "models/core/fixed_pattern_cholmod.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/grid_matrix.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_fixed_pattern_cholmod {

using condyn::test::grid_matrix;
using condyn::test::kSolveRoundoff;
using condyn::test::relative_residual;

TEST_CASE("CHOLMOD solves symmetric positive-definite systems and keeps its analysis") {
  Eigen::SparseMatrix<double> a = grid_matrix(30, 30, 0.5);
  Eigen::VectorXd b(a.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = std::sin(0.37 * static_cast<double>(i));
  FixedPatternCholmod chol;
  REQUIRE(chol.factor(a));
  const std::string ordering = chol.ordering();
  CHECK_FALSE(ordering.empty());
  Eigen::VectorXd x = b;
  chol.solve_in_place(x);
  CHECK(relative_residual(a, x, b) <= kSolveRoundoff);
  // New values on the same pattern (another cj): refactored with the same analysis.
  a = grid_matrix(30, 30, 50.0);
  REQUIRE(chol.factor(a));
  x = b;
  chol.solve_in_place(x);
  CHECK(relative_residual(a, x, b) <= kSolveRoundoff);
  CHECK(chol.factorizations() == 2);
  CHECK(chol.ordering() == ordering);
  Eigen::VectorXd wrong(3);
  CHECK_THROWS_AS(chol.solve_in_place(wrong), std::invalid_argument);
}

TEST_CASE("CHOLMOD's OpenMP loops run on the calling thread once condyn has opened it") {
  FixedPatternCholmod chol;
  REQUIRE(chol.factor(grid_matrix(10, 10, 1.0)));
  if (std::getenv("OMP_MAX_ACTIVE_LEVELS") != nullptr ||
      std::getenv("OMP_THREAD_LIMIT") != nullptr) {
    MESSAGE("OMP_MAX_ACTIVE_LEVELS or OMP_THREAD_LIMIT is set: the user's setting is kept");
    return;
  }
  // libgomp, in the process only as CHOLMOD's dependency (RTLD_NOLOAD: no new load).
  void* gomp = dlopen("libgomp.so.1", RTLD_NOW | RTLD_NOLOAD);
  if (gomp == nullptr) {
    MESSAGE("this CHOLMOD was built without OpenMP: nothing to serialize");
    return;
  }
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): dlsym returns void*
  auto levels = reinterpret_cast<int (*)()>(dlsym(gomp, "omp_get_max_active_levels"));
  const bool found = levels != nullptr;
  REQUIRE(found);
  CHECK(levels() == 0);
  dlclose(gomp);
}

TEST_CASE("CHOLMOD refuses a matrix that is not positive definite, then factors one that is") {
  FixedPatternCholmod chol;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(100);
  CHECK_THROWS_AS(chol.solve_in_place(x), std::logic_error);  // nothing factored
  // The 2D Laplacian's eigenvalues lie in (0, 8): shifted by −9 every one is negative.
  CHECK_FALSE(chol.factor(grid_matrix(10, 10, -9.0)));
  CHECK_THROWS_AS(chol.solve_in_place(x), std::logic_error);  // the failed factor is not used
  REQUIRE(chol.factor(grid_matrix(10, 10, 1.0)));
  const Eigen::VectorXd b = x;
  chol.solve_in_place(x);
  CHECK(relative_residual(grid_matrix(10, 10, 1.0), x, b) <= kSolveRoundoff);
}

TEST_CASE("the analysis lists every ordering of the build and picks the least fill") {
  const Eigen::SparseMatrix<double> a = grid_matrix(60, 60, 1.0);
  const std::vector<CholmodCandidate> candidates = cholmod_candidates(a);
  std::vector<std::string> names(candidates.size());
  std::transform(candidates.begin(), candidates.end(), names.begin(),
                 [](const CholmodCandidate& c) { return c.ordering; });
  // Debian's libcholmod3 is built with METIS and its Partition module (ldd: libmetis.so.5).
  CHECK(names == std::vector<std::string>{"amd", "metis", "nesdis"});
  for (const auto& c : candidates) {
    CAPTURE(c.ordering);
    // L has at least A's lower triangle (n + nnz below) and at most the dense triangle.
    const double n = static_cast<double>(a.rows());
    CHECK(c.factor_entries >= (static_cast<double>(a.nonZeros()) + n) / 2);
    CHECK(c.factor_entries <= n * (n + 1) / 2);
    CHECK(c.factor_bytes >= c.factor_entries * sizeof(double));
  }
  const CholmodCandidate& best = least_fill(candidates);
  for (const auto& c : candidates) CHECK(best.factor_entries <= c.factor_entries);
  FixedPatternCholmod chol;
  REQUIRE(chol.factor(a));
  CHECK(chol.ordering() == best.ordering);
  CHECK(chol.analyses() == static_cast<int>(candidates.size()));
  // An ordering named (the run's, chosen by the plan's analysis): that analysis alone.
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(a.rows());
  for (const auto& c : candidates) {
    CAPTURE(c.ordering);
    FixedPatternCholmod named(c.ordering);
    REQUIRE(named.factor(a));
    CHECK(named.analyses() == 1);
    CHECK(named.ordering() == c.ordering);
    Eigen::VectorXd x = b;
    named.solve_in_place(x);
    CHECK(relative_residual(a, x, b) <= kSolveRoundoff);
  }
  CHECK_THROWS_AS(FixedPatternCholmod("colamd"), std::invalid_argument);
  // CHOLMOD's rule (flops per entry of L at least 40) keeps this 2D factor simplicial and makes
  // a 3D mesh's, whose columns fill more, supernodal.
  CHECK_FALSE(chol.supernodal());
  FixedPatternCholmod chol3d;
  REQUIRE(chol3d.factor(grid_matrix(16, 16, 1.0, 16)));
  CHECK(chol3d.supernodal());
  // KLU's predicted L + U against CHOLMOD's L: the same ordering family factors a symmetric
  // matrix to about twice the entries in LU, so CHOLMOD's factor is the smaller (auto's rule).
  const FactorizationCandidates all = analyse_factorizations(a);
  CHECK(all.cholmod_smaller());
  CHECK(all.describe().find("CHOLMOD (" + best.ordering + ")") != std::string::npos);
}

namespace {

/// A 16 x 16 lattice with ties and Rayleigh damping (test_condensed_newton.cpp's) with these
/// [solve] keys.
test::BuiltScene tied_lattice(const std::string& solve_keys) {
  std::string extra;
  for (int i = 4; i < 16; i += 4) {
    extra += "[[constraint]]\nname = \"tie" + std::to_string(i) + "\"\nterms = { uy" +
             std::to_string(15 * 16 + i + 1) + " = 1.0, uy" + std::to_string(i + 1) + " = -1.0 }\n";
  }
  extra += "[[load]]\ndof = \"uy256\"\nvalue = { type = \"step\", amplitude = -1.0 }\n";
  std::string text = test::lattice(16, 16, extra, "rtol = 1e-8\natol = 1e-10\n" + solve_keys);
  text.replace(text.find("supports = "), 0, "damping = { rayleigh = [0.1, 0.01] }\n");
  return test::built(parse_scene_text(text, "lattice.toml"));
}

}  // namespace

TEST_CASE(
    "elimination and penalty runs agree under KLU and CHOLMOD, and auto chooses by analysis") {
  for (const char* scheme : {"elimination", "penalty"}) {
    CAPTURE(scheme);
    const std::string named = std::string("scheme = \"") + scheme + "\"\n";
    const auto klu = tied_lattice(named + "newton = \"condensed\"\nlinear_solver = \"klu\"\n");
    const auto chol = tied_lattice(named + "linear_solver = \"cholmod\"\n");
    const auto automatic = tied_lattice(named + "newton = \"condensed\"\n");
    const auto full = tied_lattice(named);
    CHECK_FALSE(plan(klu.model, klu.spec.solve).integrator.cholmod);
    const RunPlan chol_plan = plan(chol.model, chol.spec.solve);
    CHECK(chol_plan.integrator.cholmod);
    CHECK(chol_plan.integrator.condensed_newton);  // implied by "cholmod"
    // The run analyses under the ordering the plan's analysis chose, and no other.
    CHECK_FALSE(chol_plan.integrator.cholmod_ordering.empty());
    CHECK(chol_plan.factorization.reason.find("CHOLMOD (" + chol_plan.integrator.cholmod_ordering +
                                              ", ") == 0);
    // auto on the condensed matrix: CHOLMOD, its factor the smaller in the analysis it quotes.
    const RunPlan auto_plan = plan(automatic.model, automatic.spec.solve);
    CHECK(auto_plan.integrator.cholmod);
    CHECK(auto_plan.factorization.reason.find("auto: the smaller factor") != std::string::npos);
    CHECK(auto_plan.factorization.reason.find("KLU (amd)") != std::string::npos);
    // The run's memory estimate counts CHOLMOD's predicted factor, not KLU's.
    const auto chol_memory = run_memory_estimate(chol.model, chol.spec.solve);
    const auto klu_memory = run_memory_estimate(klu.model, klu.spec.solve);
    REQUIRE(chol_memory);
    REQUIRE(klu_memory);
    CHECK(chol_memory->estimate.cholmod);
    CHECK(chol_memory->estimate.factor_entries == chol_plan.factorization.factor_entries);
    CHECK_FALSE(klu_memory->estimate.cholmod);
    // auto on the full Jacobian over [u; v] (unsymmetric): KLU.
    CHECK_FALSE(plan(full.model, full.spec.solve).integrator.cholmod);
    RunHooks hooks;
    hooks.reactions = true;
    const SolveResult a = test::solved(klu.model, klu.spec.solve, hooks);
    const SolveResult b = test::solved(chol.model, chol.spec.solve, hooks);
    REQUIRE(a.summary.steps > 0);
    REQUIRE(a.trajectory.reaction.size() > 0);
    const double scale = a.trajectory.u.cwiseAbs().maxCoeff();
    REQUIRE(scale > 0.0);
    // The same Newton iteration with another backward-stable factorization: the runs differ by
    // roundoff amplified through the error control, inside 10 rtol (1e-8) of the largest value.
    CHECK((a.trajectory.u - b.trajectory.u).cwiseAbs().maxCoeff() <= 10 * 1e-8 * scale);
    CHECK((a.trajectory.reaction - b.trajectory.reaction).cwiseAbs().maxCoeff() <=
          10 * 1e-8 * a.trajectory.reaction.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("linear_solver: auto by default, refused values and cholmod where it cannot factor") {
  const std::string scene =
      "[model]\ntype = \"matrix\"\ndofs = [\"x\", \"y\"]\nmass = [[1.0, 0.0], [0.0, 1.0]]\n"
      "stiffness = [[2.0, -1.0], [-1.0, 2.0]]\n[[constraint]]\nname = \"c\"\n"
      "terms = { x = 1.0, y = 1.0 }\n[solve]\nt_end = 1.0\noutput_step = 0.5\n";
  using LinearSolver = SolveSpec::LinearSolver;
  CHECK(parse_scene_text(scene, "s.toml").solve.linear_solver == LinearSolver::automatic);
  CHECK(parse_scene_text(scene + "linear_solver = \"auto\"\n", "s.toml").solve.linear_solver ==
        LinearSolver::automatic);
  CHECK(parse_scene_text(scene + "linear_solver = \"klu\"\n", "s.toml").solve.linear_solver ==
        LinearSolver::klu);
  CHECK(parse_scene_text(scene + "linear_solver = \"cholmod\"\n", "s.toml").solve.linear_solver ==
        LinearSolver::cholmod);
  CHECK_THROWS_WITH_AS((void)parse_scene_text(scene + "linear_solver = \"umfpack\"\n", "s.toml"),
                       doctest::Contains("s.toml:12: solve.linear_solver: expected 'auto', 'klu', "
                                         "'cholmod' or 'dense'"),
                       SceneError);
  // GGL's Newton matrix is a saddle point: "cholmod" is refused naming the key.
  const auto ggl = test::built(parse_scene_text(
      scene + "scheme = \"ggl\"\nnewton = \"condensed\"\nlinear_solver = \"cholmod\"\n", "s.toml"));
  try {
    (void)plan(ggl.model, ggl.spec.solve);
    FAIL("cholmod under GGL was not refused");
  } catch (const SchemeNotApplicable& e) {
    CHECK(e.where().path == "solve.linear_solver");
    CHECK(e.where().line == 14);
    CHECK(std::string(e.what()).find("not symmetric positive definite") != std::string::npos);
  }
  // Under elimination the same model's condensed matrix is factored by CHOLMOD.
  const auto elimination = test::built(parse_scene_text(
      scene + "scheme = \"elimination\"\nlinear_solver = \"cholmod\"\n", "s.toml"));
  CHECK(plan(elimination.model, elimination.spec.solve).integrator.cholmod);
}

TEST_CASE("the memory estimate counts CHOLMOD's predicted factor in place of KLU's") {
  IntegratedSizes sizes;
  sizes.unknowns = 100;
  sizes.newton_nonzeros = 500;
  sizes.factor_entries = 1000;  // below kStreamedSolveFromEntries: KLU's factors held once
  const MemoryEstimate klu = integration_memory_estimate(ModelSizes{}, sizes);
  constexpr double kCholmodBytes = 5000;
  sizes.cholmod_factor_bytes = kCholmodBytes;
  const MemoryEstimate chol = integration_memory_estimate(ModelSizes{}, sizes);
  CHECK(chol.cholmod);
  CHECK_FALSE(klu.cholmod);
  // KLU's L and U at 12 B an entry (a double and a 32-bit index) give way to CHOLMOD's bytes; the
  // figures are whole numbers of bytes, exact in double.
  CHECK(klu.bytes - chol.bytes == 12.0 * sizes.factor_entries - kCholmodBytes);
  // CHOLMOD's symbolic analysis predicts its factor exactly: the lower bound holds it too.
  CHECK(chol.lower_bound == chol.bytes);
  CHECK(factor_name(chol) == "CHOLMOD's factor");
  CHECK(factor_name(klu) == "KLU's factors");
}

TEST_CASE("info's warning of a slow factorization: its figures, and none below the bound") {
  // The plan of the tied lattice carries the flops of the ordering it chose (CHOLMOD's count).
  const auto chol = tied_lattice("scheme = \"elimination\"\nlinear_solver = \"cholmod\"\n");
  const RunPlan chol_plan = plan(chol.model, chol.spec.solve);
  REQUIRE(chol_plan.factorization.cholmod);
  CHECK(chol_plan.factorization.factor_flops > 0.0);
  // Far below kSlowFactorSeconds at kFactorFlopRate: no warning.
  CHECK(chol_plan.factorization.factor_flops < kSlowFactorSeconds * kFactorFlopRate);
  CHECK_FALSE(factorization_time_warning(chol_plan.factorization).has_value());

  FactorizationChoice slow = chol_plan.factorization;
  slow.factor_flops = 1.5e12;  // 30 s at 5e10 flop/s, three times the bound
  const auto warning = factorization_time_warning(slow);
  REQUIRE(warning.has_value());
  CHECK(warning->find("1.5e+12 flops (CHOLMOD, " + slow.ordering + ")") != std::string::npos);
  CHECK(warning->find("at least 30 s at 5e+10 flop/s") != std::string::npos);
  // Just below the bound: none; and none when KLU factors (no flop count of its own).
  slow.factor_flops = 0.99 * kSlowFactorSeconds * kFactorFlopRate;
  CHECK_FALSE(factorization_time_warning(slow).has_value());
  slow.factor_flops = 1.5e12;
  slow.cholmod = false;
  CHECK_FALSE(factorization_time_warning(slow).has_value());
}

}  // namespace test_fixed_pattern_cholmod
