// RATTLE from the command line: `run --scheme rattle --step h` writes the columns the other
// schemes write (reactions included) and notes its step; what it cannot integrate, and a missing
// step, exit 2 naming the key.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_rattle {

using condyn::test::Result;
using condyn::test::Sandbox;

namespace {

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("run under rattle writes the other schemes' columns") {
  const Sandbox box;
  box.write("p.toml", condyn::test::kFixedStepPendulum);
  const Result ggl = box.run("run p.toml --scheme ggl --out ggl.csv");
  REQUIRE(ggl.code == 0);
  const Result r = box.run("run p.toml --scheme rattle --out r.csv");
  CHECK(r.code == 0);
  CHECK(first_line(condyn::test::slurp(box.path("r.csv"))) ==
        first_line(condyn::test::slurp(box.path("ggl.csv"))));
  CHECK(contains(r.out + r.err, "rattle: symplectic, fixed step 0.01"));
  CHECK(box.run("run p.toml --scheme rattle --step 0.005 --out s.csv").code == 0);
}

TEST_CASE("rattle's refusals and a missing step exit 2 naming the key") {
  const Sandbox box;
  std::string damped = condyn::test::kFixedStepPendulum;
  damped.replace(damped.find("[solve]"), 7,
                 "damping = { rayleigh = [0.1, 0.0] }\n[solve]\nscheme = \"rattle\"");
  box.write("d.toml", damped);
  const Result d = box.run("run d.toml --out d.csv");
  CHECK(d.code == 2);
  CHECK(contains(d.err, "d.toml:"));
  CHECK(contains(d.err, "solve.scheme"));
  CHECK(contains(d.err, "rattle integrates conservative mechanisms only"));
  std::string no_step = condyn::test::kFixedStepPendulum;
  no_step.replace(no_step.find("step = 0.01"), 11, "");
  box.write("n.toml", no_step);
  const Result n = box.run("run n.toml --scheme rattle --out n.csv");
  CHECK(n.code == 2);
  CHECK(contains(n.err, "solve.step"));
  // A file naming rattle without a step runs when the command line gives the step, or another
  // scheme (the reader refused it before the flags applied).
  std::string named = no_step;
  named.replace(named.find("[solve]"), 7, "[solve]\nscheme = \"rattle\"");
  box.write("named.toml", named);
  CHECK(box.run("run named.toml --out named.csv").code == 2);
  CHECK(box.run("run named.toml --step 0.01 --out named.csv").code == 0);
  CHECK(box.run("run named.toml --scheme ggl --out named.csv").code == 0);
}

TEST_CASE("rattle warns of a step beyond its stability limit, and its failure says why") {
  // Two unit masses on springs k = 1 and 1e6 (the stiff pair of docs/schemes.md): ω_max =
  // √(2 · 1e6) ≈ 1414 rad/s to 1e-6, so h = 0.01 gives h ω = 14 ≥ 2, and the explicit force
  // update blows up (it did at t = 1.35, advised to check the loads); h = 0.001 gives 1.4 < 2.
  const Sandbox box;
  box.write("pair.toml", condyn::test::stiff_pair_scene("scheme = \"rattle\"\n"));
  const Result beyond = box.run("run pair.toml --step 0.01 --out beyond.csv");
  CHECK(beyond.code == 1);
  CHECK(contains(beyond.err,
                 "warning: pair.toml: rattle's step 0.01 times the model's highest "
                 "frequency, omega_max = 1.41e+03"));
  CHECK(contains(beyond.err, "is 14.1, beyond the explicit force update's stability limit"));
  CHECK(contains(beyond.err, "suggestion: "));
  CHECK(contains(beyond.err.substr(beyond.err.find("suggestion: ")),
                 "a [solve] step below 2 / omega_max = 0.00141"));
  const Result within = box.run("run pair.toml --step 0.001 --out within.csv");
  CHECK(within.code == 0);
  CHECK_FALSE(contains(within.err, "stability limit"));
}

TEST_CASE("rattle's stability warning is printed once by a run that ends") {
  // The stiff pair at h = 0.0015 (h ω = 2.12 ≥ 2) grows until t ≈ 1.5 (run to 10 s it blew up
  // there); over 0.3 s it ends. The warning, printed before the run, is not repeated in the
  // summary line (it was, word for word).
  std::string scene = condyn::test::stiff_pair_scene("scheme = \"rattle\"\nstep = 0.0015\n");
  scene.replace(scene.find("t_end = 10.0"), 12, "t_end = 0.3");
  scene.replace(scene.find("output_step = 0.5"), 17, "output_step = 0.1");
  const Sandbox box;
  box.write("short.toml", scene);
  const Result r = box.run("run short.toml --out short.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string all = r.out + r.err;
  const auto first = all.find("stability limit");
  REQUIRE(first != std::string::npos);
  CHECK(all.find("stability limit", first + 1) == std::string::npos);
  CHECK(contains(r.err, "warning: short.toml: rattle's step 0.0015"));
  CHECK(contains(all, "rattle: symplectic, fixed step 0.0015"));  // the other notes stay
}

}  // namespace test_cli_rattle
