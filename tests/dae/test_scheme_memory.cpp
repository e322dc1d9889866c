// The memory estimate per scheme (dae/run/scheme_memory.hpp): each scheme's from the system it
// integrates, ordered as those systems' sizes are.

#include <doctest/doctest.h>

#include <map>
#include <string>

#include "dae/run/scheme_memory.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_scheme_memory {

namespace {

/// A tie across the lattice's top corner, so that the rows are not all single-freedom.
constexpr const char* kTie =
    "[[constraint]]\nname = \"tie\"\nterms = { ux400 = 1.0, ux399 = -1.0 }\n";

struct Sized {
  SystemSize size;
  MemoryEstimate estimate;
};

}  // namespace

TEST_CASE("the memory estimate is per scheme, from the sizes each integrates") {
  // 20 × 20 nodes: 800 DOFs, 20 supports (40 rows) and the tie.
  const SceneSpec spec = parse_scene_text(test::lattice(20, 20, kTie, ""), "lattice.toml");
  const Model model = build_model(spec);
  SchemeMemory memory(model);
  std::map<Scheme, Sized> by;
  for (Scheme s : kSchemes) {
    CAPTURE(std::string(to_string(s)));
    const SystemSize size = system_size(model, test::under(spec.solve, s));
    const MemoryEstimate e = memory(size);
    CHECK(e.newton_nonzeros == static_cast<double>(size.jacobian_nonzeros));
    CHECK(e.lower_bound < e.bytes);  // a 2D lattice fills in: the factors exceed the matrix
    by[s] = {size, e};
  }
  // The projection factors the condensed matrix [M + K, Aᵀ; A, 0] alone; every other scheme the
  // Jacobian over [u; v; ...], whose factor adds its nonzeros to the condensed one's.
  REQUIRE(by.at(Scheme::projection).size.condensed);
  const double condensed = by.at(Scheme::projection).estimate.factor_entries;
  CHECK(condensed > 0.0);
  for (const auto& [s, x] : by) {
    if (s == Scheme::projection) continue;
    const std::string name = to_string(s);  // CAPTURE's lambda cannot name a binding (clang 14)
    CAPTURE(name);
    CHECK_FALSE(x.size.condensed);
    CHECK(x.estimate.factor_entries == static_cast<double>(x.size.jacobian_nonzeros) + condensed);
  }
  // Ordered as the systems are: a system with at least another's unknowns and nonzeros (factored
  // the same way, of the model or of a reduced one alike) needs at least its memory, and more
  // when it is larger in either.
  for (const auto& [a, x] : by) {
    for (const auto& [b, y] : by) {
      if (x.size.condensed != y.size.condensed || x.size.reduced != y.size.reduced) continue;
      if (x.size.unknowns < y.size.unknowns || x.size.jacobian_nonzeros < y.size.jacobian_nonzeros)
        continue;
      const std::string pair = std::string(to_string(a)) + " against " + to_string(b);
      CAPTURE(pair);
      const bool larger =
          x.size.unknowns > y.size.unknowns || x.size.jacobian_nonzeros > y.size.jacobian_nonzeros;
      CHECK(x.estimate.bytes >= y.estimate.bytes);
      if (larger) CHECK(x.estimate.bytes > y.estimate.bytes);
    }
  }
  // Where the sizes differ, so do the figures: GGL's μ block, index1's multipliers against
  // penalty's none; the projection's condensed matrix against the Jacobians; elimination's
  // reduced model held beside the model.
  CHECK(by.at(Scheme::elimination).size.reduced);
  CHECK(by.at(Scheme::ggl).estimate.bytes > by.at(Scheme::index1).estimate.bytes);
  CHECK(by.at(Scheme::index1).estimate.bytes > by.at(Scheme::penalty).estimate.bytes);
  CHECK(by.at(Scheme::projection).estimate.bytes != by.at(Scheme::index1).estimate.bytes);
  // run checks the chosen scheme's figure: the same as the table's for that scheme.
  const auto run = run_memory_estimate(model, test::under(spec.solve, Scheme::penalty));
  REQUIRE(run.has_value());
  CHECK(run->scheme == Scheme::penalty);
  CHECK(run->estimate.bytes == by.at(Scheme::penalty).estimate.bytes);
}

TEST_CASE("the streamed copy of KLU's factors is counted where the solvers keep it") {
  IntegratedSizes sizes;
  sizes.unknowns = 1e5;
  sizes.newton_nonzeros = 1e6;
  sizes.factor_entries = 4e6;                        // above kStreamedSolveFromEntries
  sizes.factor_flops = 10.0 * sizes.factor_entries;  // a banded strip's factor: the copy is kept
  const MemoryEstimate banded = integration_memory_estimate(ModelSizes{}, sizes);
  sizes.factor_flops = 200.0 * sizes.factor_entries;  // a 2D mesh's fill: no copy
  const MemoryEstimate mesh = integration_memory_estimate(ModelSizes{}, sizes);
  // The copy costs the factor again, 12 B an entry (whole numbers of bytes, exact in double).
  CHECK(banded.bytes - mesh.bytes == 12.0 * sizes.factor_entries);
  // The lower bound holds the factor once, as large as the Newton matrix, whatever the analysis
  // predicts: the run decides on the copy from its own factor's flops.
  CHECK(banded.lower_bound == mesh.lower_bound);
  CHECK(mesh.bytes - mesh.lower_bound == 12.0 * (sizes.factor_entries - sizes.newton_nonzeros));
  // The rule at its edges: from kStreamedSolveFromEntries entries, up to
  // kStreamedSolveMostFlopsPerEntry flops an entry; an unknown count (0) keeps the copy.
  constexpr auto from = static_cast<double>(kStreamedSolveFromEntries);
  CHECK(keeps_streamed_copy(from, kStreamedSolveMostFlopsPerEntry * from));
  CHECK(keeps_streamed_copy(from, 0.0));
  CHECK_FALSE(keeps_streamed_copy(from - 1.0, 0.0));
  CHECK_FALSE(keeps_streamed_copy(from, kStreamedSolveMostFlopsPerEntry * from + 1.0));
}

TEST_CASE("the run's memory check names the scheme and refuses only below its lower bound") {
  const SceneSpec spec = parse_scene_text(test::lattice(20, 20, kTie, ""), "lattice.toml");
  const Model model = build_model(spec);
  const auto run = run_memory_estimate(model, test::under(spec.solve, Scheme::ggl));
  REQUIRE(run.has_value());
  const MemoryEstimate& e = run->estimate;
  const ModelSizes sizes = model_sizes(model);
  CHECK_FALSE(memory_refusal(sizes, e, "scheme ggl", e.lower_bound).has_value());
  const auto refusal = memory_refusal(sizes, e, "scheme ggl", 0.5 * e.lower_bound);
  REQUIRE(refusal.has_value());
  CHECK(refusal->rfind("800 DOFs and 41 constraints need at least ", 0) == 0);
  CHECK(refusal->find(" to integrate under scheme ggl (") != std::string::npos);
  // Between the lower bound and the estimate: warned about, not refused.
  const double between = 0.5 * (e.lower_bound + e.bytes);
  CHECK_FALSE(memory_refusal(sizes, e, "scheme ggl", between).has_value());
  const auto warning = memory_warning(e, "scheme ggl", between);
  REQUIRE(warning.has_value());
  CHECK(warning->rfind("integrating under scheme ggl needs about ", 0) == 0);
  CHECK_FALSE(memory_warning(e, "scheme ggl", e.bytes).has_value());
}

}  // namespace test_scheme_memory
