// `condyn sweep SWEEP.toml` (issue 46, docs/sweep.md) end to end: the command hands the sweep to
// the Python module on a local Dask cluster, writes results.csv with the contract's columns, runs
// nothing again when started on a finished folder, and refuses a bad sweep file (exit 2, the file
// and key named). Where condyn is built without its Python module, it says so (exit 1).
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_sweep {

using condyn::test::Result;
using condyn::test::Sandbox;

namespace {

/// Two runs of the two-masses scene, at two tolerances, keeping b's peak.
constexpr const char* kSweep = R"(scene = "s.toml"
[[axis]]
key = "solve.rtol"
values = [1e-6, 1e-8]
[keep]
peaks = ["b"]
)";

}  // namespace

#if CONDYN_PYTHON_BUILT

TEST_CASE("condyn sweep writes one row per run and, started again, runs nothing") {
  const Sandbox box;
  box.write("s.toml", condyn::test::kTwoMassesScene);
  box.write("study.toml", kSweep);
  const Result first = box.run("sweep study.toml --workers 2");
  CAPTURE(first.err);
  REQUIRE(first.code == 0);
  CHECK(first.err.find("sweep: 2 runs: 2 ok, 0 failed, 0 not run; 0 done before") !=
        std::string::npos);
  const std::string table = condyn::test::slurp(box.path("study/results.csv"));
  CHECK(table.substr(0, table.find('\n')) ==
        "run,solve.rtol,status,steps,wall_s,peak_b,peak_time_b");
  CHECK(table.find(",1e-06,ok,") != std::string::npos);
  CHECK(table.find(",1e-08,ok,") != std::string::npos);
  const Result again = box.run("sweep study.toml --out study");
  CAPTURE(again.err);
  REQUIRE(again.code == 0);
  CHECK(again.err.find("2 done before") != std::string::npos);
  CHECK(condyn::test::slurp(box.path("study/results.csv")) == table);
}

TEST_CASE("condyn sweep refuses a bad sweep file or flag before any run, exit 2") {
  const Sandbox box;
  box.write("s.toml", condyn::test::kTwoMassesScene);
  box.write("study.toml", condyn::test::replace(kSweep, "solve.rtol", "solve.rtoll"));
  const Result bad_key = box.run("sweep study.toml --workers 1");
  CHECK(bad_key.code == 2);
  CHECK(bad_key.err.find("study.toml: axis[1] (solve.rtoll = 1e-06): the scene refuses it") !=
        std::string::npos);
  CHECK_FALSE(std::filesystem::exists(box.path("study")));
  box.write("study.toml", kSweep);
  const Result bad_workers = box.run("sweep study.toml --workers 0");
  CHECK(bad_workers.code == 2);
  CHECK(bad_workers.err.find("--workers") != std::string::npos);
  const Result bad_address = box.run("sweep study.toml --scheduler localhost:8786");
  CHECK(bad_address.code == 2);
  CHECK(bad_address.err.find("expected an address tcp://host:port") != std::string::npos);
}

#else

TEST_CASE("condyn sweep says it needs the Python module where condyn is built without it") {
  const Sandbox box;
  box.write("study.toml", kSweep);
  const Result r = box.run("sweep study.toml");
  CHECK(r.code == 1);
  CHECK(r.err.find("built without it") != std::string::npos);
}

#endif

}  // namespace test_cli_sweep
