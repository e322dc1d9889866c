// Results streamed (issue 12, item 3): `run` writes each row as the integration reaches it when
// the result is a regular file, and the file is the one the whole-trajectory writer gives (which
// a stream output such as standard output still gets).

#include <doctest/doctest.h>

#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_cli_streaming {

using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

TEST_CASE("a streamed CSV has the bytes of the whole-result CSV, under every kind of scheme") {
  const Sandbox box;
  const std::string scene =
      std::string(CONDYN_SOURCE_DIR) + "/validation/scenes/chapter_5_6_1.toml";
  for (const char* scheme : {"elimination", "ggl", "index1", "projection"}) {
    CAPTURE(scheme);
    const Result file = box.run("run " + scene + " --scheme " + scheme + " --out streamed.csv");
    REQUIRE(file.code == 0);
    const Result whole = box.run("run " + scene + " --scheme " + scheme + " --out -");
    REQUIRE(whole.code == 0);
    CHECK(slurp(box.path("streamed.csv")) == whole.out);
  }
}

TEST_CASE("a streamed run hands out every row in order and holds no DOFs x times data") {
  const auto scene = test::built(
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/validation/scenes/chapter_5_6_1.toml"));
  for (const Scheme scheme : {Scheme::elimination, Scheme::ggl, Scheme::projection}) {
    CAPTURE(to_string(scheme));
    const SolveSpec settings = test::under(scene.spec.solve, scheme);
    const SolveResult whole = test::solved(scene.model, settings);
    std::vector<TrajectoryRow> rows;
    RunHooks hooks;
    hooks.on_row = [&rows](const TrajectoryRow& row) { rows.push_back(row); };
    const SolveResult streamed = test::solved(scene.model, settings, hooks);
    // Nothing of size n x output times in the result; times, drifts and the summary stay.
    CHECK(streamed.trajectory.u.size() == 0);
    CHECK(streamed.trajectory.v.size() == 0);
    CHECK(streamed.trajectory.reaction.size() == 0);
    CHECK(streamed.trajectory.multiplier.size() == 0);
    CHECK(streamed.trajectory.t == whole.trajectory.t);
    CHECK(streamed.trajectory.drift_position == whole.trajectory.drift_position);
    CHECK(streamed.summary.max_drift_position == whole.summary.max_drift_position);
    // The rows are the whole trajectory's columns, bit for bit, in order.
    REQUIRE(rows.size() == whole.trajectory.t.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      CHECK(rows[k].t == whole.trajectory.t[k]);
      CHECK(rows[k].u == whole.trajectory.u.col(col));
      CHECK(rows[k].v == whole.trajectory.v.col(col));
      CHECK(rows[k].reaction == whole.trajectory.reaction.col(col));
      CHECK(rows[k].multiplier == whole.trajectory.multiplier.col(col));
    }
  }
}

}  // namespace test_cli_streaming
