// The command line as users and outside checks see it (scene-format.md, "Command line"): exit
// codes, messages that name the file, the CSV columns and rows, and no lost data on failure.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/n_four_bar.hpp"
#include "tests/scene_text.hpp"

namespace test_cli {

namespace fs = std::filesystem;
using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

const std::string& kScene = condyn::test::kTwoMassesScene;

}  // namespace

TEST_CASE("run writes the contract's CSV and a one-line summary" * doctest::test_suite("smoke")) {
  const Sandbox box;
  box.write("s.toml", kScene);
  const Result r = box.run("run s.toml --out r.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("elimination: reached") != std::string::npos);
  CHECK(r.out.find("steps") != std::string::npos);
  CHECK(r.out.find("max drift position") != std::string::npos);
  const std::string csv = slurp(box.path("r.csv"));
  std::istringstream lines(csv);
  std::string header;
  std::getline(lines, header);
  CHECK(header == "t,a,b,drift_position,drift_velocity");  // default quantities
  std::vector<double> times;
  for (std::string line; std::getline(lines, line);) times.push_back(std::stod(line));
  CHECK(times == std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0});
}

TEST_CASE("run: default output name, tolerance flags, all quantities") {
  const Sandbox box;
  box.write("scene.toml",
            kScene + "[output]\nquantities = [\"velocity\", \"multiplier\", \"reaction\"]\n");
  const Result r = box.run("run scene.toml --rtol 1e-9 --atol 1e-11");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string csv = slurp(box.path("scene.csv"));
  CHECK(csv.rfind("t,vel_a,vel_b,lambda_tie,reaction_a,reaction_b\n", 0) == 0);
}

TEST_CASE("bad input: exit 2, the file and key named, existing output untouched" *
          doctest::test_suite("smoke")) {
  const Sandbox box;
  box.write("bad.toml", kScene + "[initial]\ndisplacement = { zz = 1.0 }\n");
  box.write("keep.csv", "precious\n");
  const Result r = box.run("run bad.toml --out keep.csv");
  CHECK(r.code == 2);
  CHECK(r.err.find("bad.toml") != std::string::npos);
  CHECK(r.err.find("initial.displacement.zz: no such DOF") != std::string::npos);
  CHECK(slurp(box.path("keep.csv")) == "precious\n");

  const Result missing = box.run("run nowhere.toml --out keep.csv");
  CHECK(missing.code == 2);
  CHECK(missing.err.find("nowhere.toml: cannot open") != std::string::npos);
  CHECK(slurp(box.path("keep.csv")) == "precious\n");
}

TEST_CASE("failures after parsing leave the output untouched too") {
  const Sandbox box;
  // A scene refused after parsing, by the builder: a DOF without mass that nothing holds (this
  // was a failed run, exit 1, until issue 10 made it bad input naming the key).
  box.write("s.toml", R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 0.0]]
stiffness = [[2.0, 0.0], [0.0, 0.0]]
[solve]
t_end = 1.0
output_step = 0.5
scheme = "elimination"
)");
  box.write("keep.csv", "precious\n");
  const Result r = box.run("run s.toml --out keep.csv");
  CHECK(r.code == 2);
  CHECK(r.err.find("s.toml:1: model: DOF 'b' has neither mass nor stiffness") != std::string::npos);
  CHECK(slurp(box.path("keep.csv")) == "precious\n");
}

TEST_CASE("output to a FIFO or through a symbolic link replaces neither") {
  const Sandbox box;
  box.write("s.toml", kScene);
  // A FIFO stands for /dev/null, /dev/stdout and pipes: renaming a temporary file over it would
  // replace the special file with a regular one. A reader drains it while condyn writes.
  const fs::path fifo = box.path("pipe.csv");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const std::string drained = box.path("drained.csv").string();
  const std::string reader = "timeout 20 cat '" + fifo.string() + "' > '" + drained + "' &";
  REQUIRE(std::system(reader.c_str()) == 0);
  const Result r = box.run("run s.toml --out pipe.csv");
  CHECK(r.code == 0);
  CHECK(fs::is_fifo(fs::symlink_status(fifo)));
  for (int k = 0; k < 100 && slurp(drained).find("1,") == std::string::npos; ++k) ::usleep(20000);
  CHECK(slurp(drained).rfind("t,a,b,drift_position,drift_velocity\n", 0) == 0);

  // A link keeps pointing at its file; the file gets the new rows.
  box.write("real.csv", "old\n");
  fs::create_symlink("real.csv", box.path("link.csv"));
  CHECK(box.run("run s.toml --out link.csv").code == 0);
  CHECK(fs::is_symlink(fs::symlink_status(box.path("link.csv"))));
  CHECK(slurp(box.path("real.csv")).rfind("t,a,b", 0) == 0);
}

TEST_CASE("every scheme runs from the command line" * doctest::test_suite("smoke")) {
  const Sandbox box;
  box.write("s.toml", kScene + "[output]\nquantities = [\"reaction\", \"multiplier\"]\n");
  // The Newmark family with the fixed step it needs.
  for (const char* scheme :
       {"auto", "elimination", "index1", "baumgarte", "ggl", "index2", "index3", "penalty",
        "projection", "newmark --step 0.05", "hht --step 0.05", "generalized_alpha --step 0.05"}) {
    CAPTURE(scheme);
    const Result r = box.run(std::string("run s.toml --scheme ") + scheme + " --out r.csv");
    CHECK(r.code == 0);
    CHECK(r.out.find("reached t = 1") != std::string::npos);
    const std::string csv = slurp(box.path("r.csv"));
    CHECK(csv.rfind("t,reaction_a,reaction_b,lambda_tie\n", 0) == 0);
    // The tie holds a = 0; b is free: its reaction column is exactly 0 under every scheme.
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    while (std::getline(lines, line)) {
      const auto last = line.rfind(',');
      const auto before = line.rfind(',', last - 1);
      CHECK(line.substr(before + 1, last - before - 1) == "0");
    }
  }
}

TEST_CASE("command-line errors exit 2") {
  const Sandbox box;
  box.write("s.toml", kScene);
  CHECK(box.run("run s.toml --rtol -1").code == 2);
  CHECK(box.run("run s.toml --scheme rk4").code == 2);
  CHECK(box.run("frobnicate").code == 2);
  CHECK(box.run("").code == 2);
  CHECK(box.run("--help").code == 0);
}

TEST_CASE("info classifies constraints and sizes the model" * doctest::test_suite("smoke")) {
  const Sandbox box;
  box.write("s.toml", kScene);
  const Result r = box.run("info s.toml");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("tie") != std::string::npos);
  CHECK(r.out.find("SFC") != std::string::npos);
  CHECK(r.out.find("holonomic") != std::string::npos);
  CHECK(r.out.find("scleronomic") != std::string::npos);
  CHECK(r.out.find("2 DOFs, 1 constraint;") != std::string::npos);
  CHECK(r.out.find("1 slave (chosen by column pivoting on A), 1 master\n  slaves: a\n"
                   "  masters: b\n") != std::string::npos);
  CHECK(r.out.find("system each scheme integrates") != std::string::npos);
  CHECK(r.out.find("ggl") != std::string::npos);
  CHECK(r.out.find("<- selected") != std::string::npos);
  // The memory each scheme needs, in the table, and the selected scheme's after it.
  CHECK(r.out.find("unknowns  Jacobian nonzeros  memory\n") != std::string::npos);
  CHECK(r.out.find("\nmemory: about ") != std::string::npos);
  CHECK(r.out.find(" to integrate under the selected scheme (at least ") != std::string::npos);
}

/// The Chaplygin sleigh (models/scenes/chaplygin_sleigh.toml): a nonholonomic row, which
/// elimination cannot treat. Its [solve] section last, so that a key can be appended to it.
constexpr const char* kSleigh =
    "[model]\ntype = \"sleigh\"\nmass = 1.0\ninertia = 0.5\ncontact_offset = 0.3\n\n"
    "[solve]\nt_end = 1.0\noutput_step = 0.1\n";

TEST_CASE("info marks a chosen scheme that does not apply on the first line of its reason") {
  const Sandbox box;
  box.write("p.toml", kSleigh);
  const Result r = box.run("info p.toml --scheme elimination");
  CAPTURE(r.out);
  REQUIRE(r.code == 0);
  const std::size_t row = r.out.find("\n  elimination      not applicable: ");
  REQUIRE(row != std::string::npos);
  const std::size_t end = r.out.find('\n', row + 1);
  CHECK(r.out.substr(row, end - row).find("<- selected") != std::string::npos);
  CHECK(r.out.find("\n   <- selected") == std::string::npos);
}

TEST_CASE("run --steps-out writes the drift at every internal step") {
  const Sandbox box;
  box.write("s.toml", kScene);
  const Result r = box.run("run s.toml --scheme ggl --out r.csv --steps-out steps.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string steps = slurp(box.path("steps.csv"));
  CHECK(steps.rfind("t,drift_position,drift_velocity\n", 0) == 0);
  const auto rows = std::count(steps.begin(), steps.end(), '\n') - 1;
  CHECK(rows > 5);  // more internal steps than the 5 output rows
  CHECK(r.out.find("internal steps to steps.csv") != std::string::npos);
}

TEST_CASE("the contract's example scene runs as written (scene-format.md, §5.5.1, scheme ggl)") {
  const Sandbox box;
  box.write("example.toml", R"(name = "Chapter 5.5.1: scleronomic, homogeneous SFC"

[model]
type = "truss2d"
nodes = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]   # node k (1-based) has DOFs "uxk", "uyk"
masses = [5.0, 3.0, 4.0]                          # lumped point mass per node, both directions
members = [
  { nodes = [1, 2], EA = 100.0 },
  { nodes = [2, 3], EA = 50.0 },
  { nodes = [1, 3], EA = 282.842712474619 },
]

[[load]]
dof = "ux3"
value = { type = "step", amplitude = 2.0 }

[[load]]
dof = "uy3"
value = { type = "step", amplitude = 1.0 }

[[constraint]]
name = "pin_x"
terms = { ux1 = 1.0 }          # 1.0 * ux1 = value (default 0: homogeneous)

[[constraint]]
terms = { uy1 = 1.0 }

[[constraint]]
terms = { uy2 = 1.0 }

[solve]
t_end = 10.0
output_step = 0.1
scheme = "ggl"
rtol = 1e-8
atol = 1e-10
)");
  const Result r = box.run("run example.toml --out e.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.rfind("ggl:", 0) == 0);
  const std::string csv = slurp(box.path("e.csv"));
  CHECK(csv.rfind("t,ux1,uy1,ux2,uy2,ux3,uy3,drift_position,drift_velocity\n", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 101);  // header + t = 0, 0.1, ..., 10
  CHECK(csv.find("\n10,") != std::string::npos);               // the last row is t_end
}

TEST_CASE("compare: default scene, named folder, bad options refused") {
  const Sandbox box;
  const Result r = box.run(
      "compare --tolerances 1e-4,1e-7 --repeats 1 --schemes elimination,ggl --no-plots "
      "--out-dir out");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("reference: exact modal solution") != std::string::npos);
  CHECK(r.err.find("[4/4] ggl rtol 1.0e-07") != std::string::npos);  // progress
  const std::string runs = slurp(box.path("out/runs.csv"));
  CHECK(std::count(runs.begin(), runs.end(), '\n') == 1 + 4);
  CHECK(fs::exists(box.path("out/runs.json")));
  CHECK(fs::exists(box.path("out/drift_ggl.csv")));

  CHECK(box.run("compare --tolerances abc").code == 2);
  CHECK(box.run("compare --tolerances 2").code == 2);
  CHECK(box.run("compare --schemes elimination,rk4").code == 2);
  CHECK(box.run("compare --schemes auto").code == 2);
  CHECK(box.run("compare --repeats 0").code == 2);
  CHECK(box.run("compare missing.toml").code == 2);
}

TEST_CASE("a scheme that cannot treat the scene is bad input: exit 2 with the reason") {
  const Sandbox box;
  const std::string sleigh =
      std::string(CONDYN_SOURCE_DIR) + "/models/scenes/chaplygin_sleigh.toml";
  box.write("keep.csv", "precious\n");
  const Result r = box.run("run '" + sleigh + "' --scheme elimination --out keep.csv");
  CHECK(r.code == 2);
  CHECK(r.err.find("chaplygin_sleigh.toml: --scheme: elimination cannot treat a nonholonomic "
                   "constraint") != std::string::npos);
  CHECK(r.err.find("§5.3.1") != std::string::npos);
  CHECK(slurp(box.path("keep.csv")) == "precious\n");
  // Chosen in the scene: the refusal names the key's line.
  box.write("p.toml", std::string(kSleigh) + "scheme = \"elimination\"\n");
  const Result s = box.run("run p.toml --out keep.csv");
  CAPTURE(s.err);
  CHECK(s.code == 2);
  CHECK(s.err.find("error: p.toml:10: solve.scheme: elimination cannot treat a nonholonomic") !=
        std::string::npos);
  CHECK(slurp(box.path("keep.csv")) == "precious\n");
  const Result c = box.run("compare '" + sleigh + "' --schemes elimination --no-plots");
  CHECK(c.code == 2);
  CHECK(c.err.find("no requested scheme applies to this scene") != std::string::npos);
  CHECK(c.err.find("elimination: elimination cannot treat a nonholonomic") != std::string::npos);
}

TEST_CASE("elimination on a nonlinear scene: coordinate partitioning, in run and info") {
  const Sandbox box;
  const std::string four_bar = std::string(CONDYN_SOURCE_DIR) + "/models/scenes/four_bar.toml";
  const Result r = box.run("run '" + four_bar + "' --scheme elimination --out r.csv");
  CAPTURE(r.out);
  CAPTURE(r.err);
  CHECK(r.code == 0);
  CHECK(r.out.find("elimination: reached t = 5") != std::string::npos);
  CHECK(r.out.find("coordinate partitioning: 1 independent of 8 coordinates") != std::string::npos);
  CHECK(r.out.find(" re-partition") != std::string::npos);
  CHECK(slurp(box.path("r.csv")).find("reaction_") != std::string::npos);
  const Result i = box.run("info '" + four_bar + "' --scheme elimination");
  CAPTURE(i.out);
  CHECK(i.code == 0);
  CHECK(i.out.find("scheme: elimination (requested)") != std::string::npos);
  CHECK(i.out.find("elimination: coordinate partitioning, 1 independent coordinate") !=
        std::string::npos);
  CHECK(i.out.find("  independent: ") != std::string::npos);
}

TEST_CASE("info on a nonlinear scene: classes, and a requested scheme that does not apply") {
  const Sandbox box;
  const std::string sleigh =
      std::string(CONDYN_SOURCE_DIR) + "/models/scenes/chaplygin_sleigh.toml";
  const Result r = box.run("info '" + sleigh + "' --scheme elimination");
  CHECK(r.code == 0);
  CHECK(r.out.find("nonholonomic") != std::string::npos);
  CHECK(r.out.find("not integrable") != std::string::npos);
  CHECK(r.out.find("scheme: elimination (requested; not applicable to this scene") !=
        std::string::npos);
  CHECK(r.out.find("  slaves: ") == std::string::npos);  // no master-slave split to show
  CHECK(r.out.find("classed by their integrated form") == std::string::npos);
  // auto's reason mentions eliminated rows only where there are some (the sleigh has none).
  const Result a = box.run("info '" + sleigh + "' --scheme auto");
  CHECK(a.out.find("scheme: ggl (nonlinear model") != std::string::npos);
  CHECK(a.out.find("constant linear rows eliminated") == std::string::npos);
  const Result crank = box.run("info '" + std::string(CONDYN_SOURCE_DIR) +
                               "/models/scenes/slider_crank.toml' --scheme auto");
  CHECK(crank.out.find("; its constant linear rows eliminated where that stays sparse") !=
        std::string::npos);
}

TEST_CASE(
    "compare on A02, whose singular positions fail every BDF reference, takes generalized-α's") {
  // IFToMM A02 (N = 40) over its first passage (t = 0.72): GGL, projection and index1 at rtol
  // 1e-10 fail there; the reference is generalized_alpha at 1/64 of the refined output interval
  // (0.05 / 4 / 64 = 1.95e-4), with its own error from a run at twice the step (observed
  // 2.3e-8 in u: the runs scored are far from it).
  const Sandbox box;
  std::string scene = condyn::test::n_four_bar(40);
  scene.replace(scene.find("t_end = 5.0"), 11, "t_end = 1.0");
  box.write("a02.toml", scene);
  const Result r = box.run(
      "compare a02.toml --tolerances 1e-8 --schemes generalized_alpha --repeats 1 --no-plots "
      "--out-dir out");
  CAPTURE(r.out);
  CAPTURE(r.err);
  CHECK(r.code == 0);
  CHECK(r.out.find("reference: generalized_alpha at the fixed step 1.95e-04 (its own relative "
                   "errors about u ") != std::string::npos);
  CHECK(r.out.find("failed: ggl: IDASolve failed") != std::string::npos);
  CHECK(r.out.find("; projection: CVode failed") != std::string::npos);
  const auto row = r.out.find("\ngeneralized_alpha  1e-08  ");
  REQUIRE(row != std::string::npos);
  const double error_u = std::stod(r.out.substr(row + 26, 8));
  CHECK(error_u > 0.0);
  CHECK(error_u < 1e-5);  // observed 2.9e-7
  // Reactions outside the passage's near_singular rows, where the state determines them: observed
  // 1.2e-5 (every A02 run read about 0.35 over 20 s with those rows scored).
  const double error_reaction = std::stod(r.out.substr(row + 44, 8));
  CHECK(error_reaction < 1e-3);
}

TEST_CASE("compare without a reference says which runs failed, at what rtol, and what to try") {
  // A pendulum struck by a load of 1e300 at t = 0.5: every tight reference run (ggl, then
  // projection, then index1) fails there at once (the pulled pendulum, which used to serve
  // here, costs projection 10⁵ steps since references fall back).
  const Sandbox box;
  box.write("s.toml", R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }]
[[load]]
dof = "uy2"
value = { type = "step", amplitude = 1e300, start = 0.5 }
[solve]
t_end = 1.0
output_step = 0.1
)");
  const Result r = box.run("compare s.toml --tolerances 1e-4 --schemes ggl --no-plots");
  CAPTURE(r.err);
  CHECK(r.code == 1);
  CHECK(r.err.find("no reference solution: there is no exact one (the model is nonlinear") !=
        std::string::npos);
  CHECK(r.err.find("the tight reference runs failed at rtol 1.0e-06 (1/100 of the smallest "
                   "--tolerances value): ggl: IDASolve failed") != std::string::npos);
  CHECK(r.err.find("; projection: CVode failed") != std::string::npos);
  CHECK(r.err.find("; index1: ") != std::string::npos);
  CHECK(r.err.find("--scheme ggl --rtol 1.0e-06 --atol 1.0e-08 shows the same") !=
        std::string::npos);
  CHECK(r.err.find("a looser smallest tolerance, or a t_end the scene reaches") !=
        std::string::npos);
}

TEST_CASE("a run that fails midway keeps its rows in FILE.partial.csv and says what to try") {
  const Sandbox box;
  // A rheonomic row pulls the pendulum's mass straight down at unit speed: at t = 1 the rod is
  // vertical, its row becomes parallel to the pull's, and no motion satisfies both beyond it:
  // the bridge across that singular configuration (dae/integrators/passage_bridge.hpp) fails
  // there too.
  box.write("s.toml", condyn::test::kPulledPendulumScene);
  box.write("out.csv", "precious\n");
  const Result r = box.run("run s.toml --out out.csv");
  CAPTURE(r.err);
  CHECK(r.code == 1);
  CHECK(r.err.find("s.toml: integration failed: under ggl") != std::string::npos);
  CHECK(r.err.find("reached t = ") != std::string::npos);
  CHECK(r.err.find("bridging the near-singular configuration entered at t = 0.99") !=
        std::string::npos);
  CHECK(r.err.find("suggestion: repeated convergence or error-test failures") != std::string::npos);
  CHECK(r.err.find("out.partial.csv") != std::string::npos);
  CHECK(slurp(box.path("out.csv")) == "precious\n");
  const std::string partial = slurp(box.path("out.partial.csv"));
  CHECK(partial.rfind("t,ux1,uy1,ux2,uy2,drift_position,drift_velocity\n", 0) == 0);
  // Rows at t = 0, 0.1, ..., 0.9: up to the singular time, none beyond it, no NaN.
  CHECK(std::count(partial.begin(), partial.end(), '\n') == 1 + 10);
  CHECK(partial.find("nan") == std::string::npos);
  // The row at 0.9, in the shortest form that reads back as that double.
  CHECK(partial.find("\n0.9,") != std::string::npos);
}

TEST_CASE("stress: unknown families are usage errors, named") {
  const Sandbox box;
  const Result r = box.run("stress --families stiffness,bogus --no-plots");
  CHECK(r.code == 2);
  CHECK(r.err.find("unknown stress family 'bogus'") != std::string::npos);
  CHECK(r.err.find("expected stiffness, mass_ratio") != std::string::npos);
}

TEST_CASE("stress --schemes: runs only under the schemes named, and refuses what it cannot run") {
  const Sandbox box;
  const Result r = box.run("stress --families redundancy --schemes penalty,ggl --no-plots");
  REQUIRE(r.code == 0);
  const std::string csv = slurp(box.path("condyn-out/stress/stress.csv"));
  // redundancy's six cases run every scheme: here ggl and penalty, six rows each, no other.
  std::istringstream rows(csv);
  std::string row;
  std::getline(rows, row);  // header
  int ggl = 0, penalty = 0, other = 0;
  while (std::getline(rows, row)) {
    if (row.find(",ggl,") != std::string::npos)
      ++ggl;
    else if (row.find(",penalty,") != std::string::npos)
      ++penalty;
    else
      ++other;
  }
  CHECK(ggl == 6);
  CHECK(penalty == 6);
  CHECK(other == 0);
  for (const auto& refusal : std::vector<std::pair<std::string, std::string>>{
           {"--schemes newmark", "stress does not run 'newmark' (it runs elimination, index1"},
           {"--schemes auto", "name schemes, not 'auto'"},
           {"--schemes ggl,bogus", "unknown scheme 'bogus'"},
           {"--families penalty_weight --schemes ggl",
            "no case of the families asked for runs under 'ggl'"}}) {
    const std::string& flags = refusal.first;  // (clang 14: no structured binding in CAPTURE)
    CAPTURE(flags);
    const Result bad = box.run("stress --no-plots --out-dir refused " + flags);
    CHECK(bad.code == 2);
    CHECK(bad.err.find("--schemes: " + refusal.second) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(box.path("refused")));
  }
}

}  // namespace test_cli
