// The build's checks on models beyond the old fixed limits (5000 DOFs or constraints, 4e6
// constraint-DOF pairs in one rank-check group): the sparse rank check names the redundant row
// of a large coupled group, and the size is judged by a memory estimate instead of a count.

#include <doctest/doctest.h>

#include <string>

#include "models/assembly/build_model.hpp"
#include "models/core/memory_estimate.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/scene_errors.hpp"

using namespace condyn;

namespace test_sparse_checks {

using condyn::test::lattice;

namespace {

/// Ties along the top row of a 100 × 100 lattice, ux_k = uy_k = ux_(k+1) for nodes 9902 …
/// 10000: 197 rows chained over 198 DOFs, one group of 39,006 constraint-DOF pairs (beyond the
/// dense block, so SuiteSparseQR factors it); then 'again', twice the row 't50'.
std::string chain_with_duplicate() {
  std::string c;
  int row = 0;
  for (int node = 9902; node <= 10000; ++node) {
    const std::string x = "ux" + std::to_string(node), y = "uy" + std::to_string(node);
    c += "[[constraint]]\nname = \"t" + std::to_string(++row) + "\"\nterms = { " + x + " = 1.0, " +
         y + " = -1.0 }\n";
    if (node < 10000) {
      c += "[[constraint]]\nname = \"t" + std::to_string(++row) + "\"\nterms = { " + y +
           " = 1.0, ux" + std::to_string(node + 1) + " = -1.0 }\n";
    }
  }
  c += "[[constraint]]\nname = \"again\"\nterms = { uy9926 = 2.0, ux9927 = -2.0 }\n";
  return c;
}

}  // namespace

TEST_CASE("a 20,000-DOF lattice with a redundant tie builds and the redundant row is named") {
  // Before: refused as "20000 DOFs: more than condyn's limit of 5000".
  const std::string drop = lattice(100, 100, chain_with_duplicate(), "redundant = \"drop\"\n");
  BuildReport report;
  const Model model = build_model(parse_scene_text(drop, "big.toml"), report);
  CHECK(model.dofs() == 20000);
  // 200 supports (left column, both directions) + 197 ties + 'again' − the dropped one.
  CHECK(model.constraint_count() == 200 + 197);
  REQUIRE(report.dropped_constraints.size() == 1);
  // 't50' is uy9926 − ux9927; 'again' is twice it: one of the two is dropped, named with the other.
  const std::string& dropped = report.dropped_constraints.front();
  CHECK((dropped ==
             "'again' (a combination of 't50'; their reactions carry its force too: not unique)" ||
         dropped ==
             "'t50' (a combination of 'again'; their reactions carry its force too: not unique)"));
  // Without the request, the pair is refused, both named, with the remedy.
  try {
    (void)build_model(parse_scene_text(lattice(100, 100, chain_with_duplicate(), ""), "big.toml"));
    FAIL("a dependent pair was accepted");
  } catch (const SceneError& e) {
    const std::string what = e.what();
    CHECK(what.find("linearly dependent (constraint matrix rank 397 < 398)") != std::string::npos);
    CHECK(what.find("'t50'") != std::string::npos);
    CHECK(what.find("'again'") != std::string::npos);
    CHECK(what.find("redundant = \"drop\"") != std::string::npos);
  }
}

TEST_CASE("the size of a model is judged by a memory estimate against the available memory") {
  const Model model = build_model(parse_scene_text(lattice(100, 100, "", ""), "big.toml"));
  const ModelSizes sizes = model_sizes(model);
  CHECK(sizes.dofs == 20000.0);
  CHECK(sizes.constraints == 200.0);
  // Before a scheme is chosen, the least any scheme holds: elimination's 2(n − m) unknowns with a
  // Newton matrix of its diagonal alone, beside the model's matrices.
  const MemoryEstimate e = least_memory_estimate(sizes);
  CHECK(e.newton_nonzeros == 2.0 * (20000.0 - 200.0));
  CHECK(e.lower_bound == e.bytes);
  // It fits in a gigabyte; it does not fit in a megabyte, and the refusal says why in figures.
  CHECK_FALSE(memory_refusal(sizes, e, "any scheme", 1e9).has_value());
  const auto refusal = memory_refusal(sizes, e, "any scheme", 1e6);
  REQUIRE(refusal.has_value());
  CHECK(refusal->rfind("20000 DOFs and 200 constraints need at least ", 0) == 0);
  CHECK(refusal->find(" to integrate under any scheme (") != std::string::npos);
  CHECK(refusal->find("more than the 1.0 MB this machine has available "
                      "(MemAvailable in /proc/meminfo, with what condyn holds already)") !=
        std::string::npos);
  // Beyond the process itself (the estimate of an empty model), linear in the sizes: a model
  // twice as large needs twice the memory.
  ModelSizes twice = sizes;
  for (double* v : {&twice.dofs, &twice.constraints, &twice.nnz_mass, &twice.nnz_stiffness,
                    &twice.nnz_constraints})
    *v *= 2.0;
  const double process = least_memory_estimate(ModelSizes{}).bytes;
  CHECK(least_memory_estimate(twice).bytes - process == doctest::Approx(2.0 * (e.bytes - process)));
}

TEST_CASE("the available memory is read from /proc/meminfo") {
  const auto available = available_memory_bytes();
  REQUIRE(available.has_value());  // Linux, where condyn runs
  CHECK(*available > 0.0);
  CHECK(format_bytes(1.5e9) == "1.5 GB");
  CHECK(format_bytes(999.0) == "999.0 B");
}

TEST_CASE("[initial] project on a 20,000-DOF lattice: the sparse least-change step") {
  // 200 supports and one tie over 20,000 free DOFs: a 201 x 20,000 block, beyond the dense
  // step's 4e6 entries (refused before as "project = true factors the dense constraint
  // Jacobian"). The tie ux10000 = ux9999 with ux10000 given 0.1 and unit masses: the least
  // mass-weighted change moves ux9999 alone, to 0.1; the supports hold their DOFs at 0.
  const std::string extra =
      "[[constraint]]\nname = \"tie\"\nterms = { ux10000 = 1.0, ux9999 = -1.0 }\n"
      "[initial]\nproject = true\ndisplacement = { ux10000 = 0.1 }\n";
  BuildReport report;
  const Model model =
      build_model(parse_scene_text(lattice(100, 100, extra, ""), "big.toml"), report);
  const auto at = [&model](const std::string& dof) { return model.u0[model.dof_at(dof)]; };
  CHECK(at("ux10000") == 0.1);  // given: kept exactly
  // One Gauss-Newton step of a linear row, solved through B Bᵀ (condition 1 here): roundoff of 0.1.
  CHECK(at("ux9999") == doctest::Approx(0.1).epsilon(1e-14));
  CHECK(at("ux1") == 0.0);
  CHECK(model.u0.cwiseAbs().sum() == doctest::Approx(0.2).epsilon(1e-14));
  CHECK(report.initial_projection.find("moved 1 DOF") != std::string::npos);
}

namespace {

/// A chain of n DOFs from Matrix Market files: K the fixed-free spring chain, M tridiagonal with
/// diagonal 4 and off-diagonal `coupling` (positive definite for |coupling| < 2), except that the
/// first 2 x 2 block is [[1, 1], [1, 1]], uncoupled from the rest, when `singular` (positive
/// semi-definite, M x = 0 for x = e1 − e2).
std::string chain_scene(const test::Sandbox& box, int n, bool singular) {
  std::string m = "%%MatrixMarket matrix coordinate real symmetric\n" + std::to_string(n) + " " +
                  std::to_string(n) + " " + std::to_string(2 * n - 1) + "\n";
  std::string k = m;
  for (int i = 1; i <= n; ++i) {
    const bool block = singular && i <= 2;
    m += std::to_string(i) + " " + std::to_string(i) + (block ? " 1.0\n" : " 4.0\n");
    k += std::to_string(i) + " " + std::to_string(i) + (i < n ? " 2.0\n" : " 1.0\n");
    if (i < n) {
      m += std::to_string(i + 1) + " " + std::to_string(i) +
           (singular && i == 2 ? " 0.0\n" : " 1.0\n");
      k += std::to_string(i + 1) + " " + std::to_string(i) + " -1.0\n";
    }
  }
  (void)box.write("M.mtx", m);
  (void)box.write("K.mtx", k);
  return box
      .write("chain.toml",
             "[model]\ntype = \"matrix\"\nmass = { file = \"M.mtx\" }\n"
             "stiffness = { file = \"K.mtx\" }\n[solve]\nt_end = 1.0\noutput_step = 0.1\n")
      .string();
}

}  // namespace

TEST_CASE(
    "a full mass matrix beyond the dense check: sparse LDLt decides, or a warning says why not") {
  // 2,100 DOFs: 4.4e6 entries as a dense matrix, beyond the dense eigen-check (skipped silently
  // before). Positive definite (diagonally dominant): nothing to say.
  test::Sandbox box;
  BuildReport report;
  (void)build_model(parse_scene_file(chain_scene(box, 2100, false)), report);
  CHECK(report.warnings.empty());
  // Singular along e1 − e2 (the [[1, 1], [1, 1]] block): the LDLt pivot of DOF 2 is 0.
  BuildReport singular;
  (void)build_model(parse_scene_file(chain_scene(box, 2100, true)), singular);
  REQUIRE(singular.warnings.size() == 1);
  CHECK(singular.warnings.front().find("the mass matrix may be singular") != std::string::npos);
}

TEST_CASE("massless DOFs beyond the dense kernel: those in no constraint are named") {
  // 1,100 massless nodes in a zigzag (bars stiff in x and y), the first 1,000 supported: 2,000
  // support rows on 2,200 massless DOFs (4.4e6 entries, beyond the dense kernel, skipped silently
  // before). The 200 DOFs of nodes 1001 ... 1100 appear in no constraint, and their bars (a
  // hinged chain) do not hold them: named.
  std::string nodes, masses, members, supports;
  for (int k = 1; k <= 1100; ++k) {
    nodes += std::string(k > 1 ? ", " : "") + "[" + std::to_string(k) + ".0, " +
             std::to_string(k % 2) + ".0]";
    masses += std::string(k > 1 ? ", " : "") + "0.0";
    if (k > 1)
      members += std::string(k > 2 ? ", " : "") + "{ nodes = [" + std::to_string(k - 1) + ", " +
                 std::to_string(k) + "], EA = 1.0 }";
    if (k <= 1000) supports += std::string(k > 1 ? ", " : "") + std::to_string(k);
  }
  const std::string scene = "[model]\ntype = \"truss2d\"\nnodes = [" + nodes + "]\nmasses = [" +
                            masses + "]\nmembers = [" + members + "]\nsupports = [" + supports +
                            "]\n[solve]\nt_end = 1.0\noutput_step = 0.1\n";
  std::string error;
  try {
    (void)build_model(parse_scene_text(scene, "massless.toml"));
  } catch (const SceneError& e) {
    error = e.what();
  }
  CAPTURE(error);
  CHECK(error.find("massless.toml:") == 0);
  CHECK(error.find("model.masses") != std::string::npos);
  CHECK(error.find("200 DOFs (ux1001, uy1001, ux1002") != std::string::npos);
  CHECK(error.find("have no mass and no constraint, and their stiffness block K_hh is singular") !=
        std::string::npos);
}

TEST_CASE("a DOF nothing acts on is refused before the checks that grow with the model") {
  // 1,000 DOFs from files, M and K diagonal except on DOF 7, which no entry reaches. K also has
  // an entry beyond its 2 x 2 minor: the definiteness check (LDLt, after the names are indexed)
  // refused that first; now the unreached DOF, found in O(nnz + n) right after reading, is.
  test::Sandbox box;
  const int n = 1000;
  std::string m = "%%MatrixMarket matrix coordinate real symmetric\n" + std::to_string(n) + " " +
                  std::to_string(n) + " " + std::to_string(n - 1) + "\n";
  std::string k = "%%MatrixMarket matrix coordinate real symmetric\n" + std::to_string(n) + " " +
                  std::to_string(n) + " " + std::to_string(n) + "\n";
  for (int i = 1; i <= n; ++i) {
    if (i == 7) continue;
    m += std::to_string(i) + " " + std::to_string(i) + " 1.0\n";
    k += std::to_string(i) + " " + std::to_string(i) + " 2.0\n";
  }
  k += "2 1 5.0\n";  // |5| > sqrt(2 · 2)
  (void)box.write("M.mtx", m);
  (void)box.write("K.mtx", k);
  const std::string model =
      "[model]\ntype = \"matrix\"\nmass = { file = \"M.mtx\" }\nstiffness = { file = \"K.mtx\" }\n";
  const std::string solve = "[solve]\nt_end = 1.0\noutput_step = 0.1\n";
  const auto error_of = [&](const std::string& scene) {
    return test::file_build_error(box.write("s.toml", scene).string());
  };
  const std::string unreached = error_of(model + solve);
  CAPTURE(unreached);
  CHECK(unreached.find("s.toml:1: model: DOF 'u7' has neither mass nor stiffness nor damping nor "
                       "a constraint: its motion is undefined") != std::string::npos);
  // A constraint that names u7 reaches it: the build goes on to the next refusal, K's entry.
  const std::string tied = error_of(model +
                                    "[[constraint]]\nname = \"tie\"\nterms = { u7 = 1.0, u8 = "
                                    "-1.0 }\n" +
                                    solve);
  CAPTURE(tied);
  CHECK(tied.find("K.mtx is not positive semi-definite: |entry (2,1)| = 5") != std::string::npos);
  // So does a constraint block with a coefficient in u7's column; a zero coefficient does not.
  const auto block = [&](const std::string& value) {
    (void)box.write("A.mtx", "%%MatrixMarket matrix coordinate real general\n1 " +
                                 std::to_string(n) + " 2\n1 7 " + value + "\n1 8 -1.0\n");
    return error_of(model + "[[constraint_block]]\nfile = \"A.mtx\"\n" + solve);
  };
  CHECK(block("1.0").find("is not positive semi-definite") != std::string::npos);
  CHECK(block("0.0").find("DOF 'u7' has neither mass nor stiffness") != std::string::npos);
}

}  // namespace test_sparse_checks
