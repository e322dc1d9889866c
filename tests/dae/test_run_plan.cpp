// The run plan (dae/run/run_plan.hpp): every decision of a run made once and held as a value,
// which `info` and `run` read alike; execute() runs it and returns its notes as structured
// entries.

#include "dae/run/run_plan.hpp"

#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "models/scene/scene_parser.hpp"
#include "src/reports/info_report.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_run_plan {

using test::driven_pendulum_scene;
using test::kTwoMassesScene;

namespace {

/// Three masses on springs, u1 held: `mass2` the middle mass. With 1e-20 beside 2 and 1, the
/// reduced mass matrix is singular to roundoff: elimination refuses it, GGL integrates it.
SceneSpec held_chain(const std::string& mass2, const std::string& scheme) {
  return parse_scene_text(R"([model]
type = "matrix"
dofs = ["u1", "u2", "u3"]
mass = [[2.0, 0.0, 0.0], [0.0, )" +
                              mass2 +
                              R"(, 0.0], [0.0, 0.0, 1.0]]
stiffness = [[400.0, -200.0, 0.0], [-200.0, 400.0, -200.0], [0.0, -200.0, 200.0]]
[[load]]
dof = "u3"
value = 10.0
[[constraint]]
terms = { u1 = 1.0 }
[solve]
scheme = ")" + scheme + R"("
t_end = 1.0
output_step = 0.25
)",
                          "chain.toml");
}

/// `info`'s line "scheme: NAME (REASON...".
std::string info_scheme_line(const test::BuiltScene& scene, const SolveSpec& settings) {
  std::ostringstream out;
  print_info(out, scene.model, scene.report, settings);
  const std::string text = out.str();
  const auto at = text.find("scheme: ");
  REQUIRE(at != std::string::npos);
  return text.substr(at, text.find('\n', at) - at);
}

}  // namespace

TEST_CASE("a plan holds the decisions it made once: the treatment, the reduction, its ODE") {
  SUBCASE("the mixed treatment of a nonlinear model's linear rows") {
    const auto scene = test::built(parse_scene_text(driven_pendulum_scene(""), "driven.toml"));
    SchemeDecisions decisions(scene.model);
    const RunPlan p = plan(scene.model, scene.spec.solve, decisions);
    CHECK(p.scheme == Scheme::ggl);
    REQUIRE(p.mixed());
    CHECK(p.treatment->eliminated.size() == 2);
    // The same object the decisions hold: the choice and the run's set-up read one
    // treat_constraints (a second computation would be another object).
    CHECK(p.treatment.get() == decisions.treatment().get());
    const RunPlan copy = p;  // copies share it
    CHECK(copy.treatment.get() == p.treatment.get());
  }
  SUBCASE("elimination's reduction and its ODE") {
    const auto scene = test::built(parse_scene_text(kTwoMassesScene, "two.toml"));
    SchemeDecisions decisions(scene.model);
    const RunPlan p = plan(scene.model, scene.spec.solve, decisions);
    CHECK(p.scheme == Scheme::elimination);
    CHECK_FALSE(p.mixed());
    REQUIRE(p.reduced != nullptr);
    CHECK(p.reduced.get() == decisions.reduced(scene.spec.solve.slaves).get());
    CHECK(p.reduced_ode.get() == decisions.reduced_ode(scene.spec.solve.slaves).get());
  }
}

TEST_CASE("execute runs a plan as solve() does, again and again with the same rows") {
  for (const std::string& scene_text : {kTwoMassesScene, driven_pendulum_scene("")}) {
    const auto scene = test::built(parse_scene_text(scene_text, "scene.toml"));
    const RunPlan p = plan(scene.model, scene.spec.solve);
    CAPTURE(to_string(p.scheme));
    const SolveResult first = execute(p), second = execute(p);
    const SolveResult alone = test::solved(scene.model, scene.spec.solve);
    REQUIRE(first.ok());
    CHECK(first.scheme == p.scheme);
    // One deterministic computation three times: bit for bit the same rows (elimination's ODE is
    // copied for each run, so nothing of one run is left in the next).
    CHECK(first.trajectory.u == second.trajectory.u);
    CHECK(first.trajectory.u == alone.trajectory.u);
    CHECK(first.trajectory.reaction == alone.trajectory.reaction);
    CHECK(first.summary.notes == alone.summary.notes);
  }
}

TEST_CASE("info and run report the same scheme and reason, from the same plan") {
  struct Case {
    SceneSpec spec;
    Scheme scheme;
  };
  const Case cases[] = {
      {parse_scene_text(kTwoMassesScene, "two.toml"), Scheme::elimination},
      {parse_scene_text(driven_pendulum_scene(""), "driven.toml"), Scheme::ggl},
      {parse_scene_text(driven_pendulum_scene("scheme = \"baumgarte\"\n"), "driven.toml"),
       Scheme::baumgarte},
      // auto chose elimination, whose reduction is refused: GGL, said by both.
      {held_chain("1e-20", "auto"), Scheme::ggl},
  };
  for (const Case& c : cases) {
    const auto scene = test::built(c.spec);
    const RunPlan p = plan(scene.model, scene.spec.solve);
    CAPTURE(p.reason);
    CHECK(p.scheme == c.scheme);
    CHECK(info_scheme_line(scene, scene.spec.solve) ==
          "scheme: " + std::string(to_string(p.scheme)) + " (" + p.reason + ")");
    const SolveResult run = execute(p);
    CHECK(run.scheme == p.scheme);
    CHECK(run.summary.scheme == to_string(p.scheme));
  }
}

TEST_CASE("auto's fallback is planned: GGL with a multiplier per row, noted first") {
  const auto scene = test::built(held_chain("1e-20", "auto"));
  const RunPlan p = plan(scene.model, scene.spec.solve);
  REQUIRE(p.fallback);
  CHECK(p.reason == *p.fallback);
  CHECK(p.fallback->find("auto: elimination refused (the reduced mass matrix is singular") == 0);
  CHECK(p.settings.treatment == SolveSpec::Treatment::multipliers);
  CHECK_FALSE(p.mixed());
  CHECK(p.reduced == nullptr);
  const SolveResult run = test::solved(scene.model, scene.spec.solve);
  REQUIRE_FALSE(run.summary.notes.empty());
  CHECK(run.summary.notes.front() == RunNote{RunNote::Kind::fallback, *p.fallback});

  // Named, the same refusal is the plan's, and execute() throws it as bad input.
  const auto named = test::built(held_chain("1e-20", "elimination"));
  const RunPlan refused = plan(named.model, named.spec.solve);
  REQUIRE(refused.refusal);
  CHECK(refused.refusal->find("the reduced mass matrix is singular") == 0);
  CHECK_THROWS_AS((void)execute(refused), SchemeNotApplicable);
}

TEST_CASE("a scheme refused outright is planned with its refusal, which execute throws") {
  // Elimination on a nonholonomic row (penalty on a nonlinear model was refused outright before
  // it became the augmented Lagrangian).
  const auto scene = test::built(
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/chaplygin_sleigh.toml"));
  const RunPlan p = plan(scene.model, test::under(scene.spec.solve, Scheme::elimination));
  REQUIRE(p.refusal);
  CHECK(*p.refusal == *scheme_refusal(scene.model, Scheme::elimination));
  CHECK_THROWS_WITH_AS((void)execute(p), p.refusal->c_str(), SchemeNotApplicable);
}

TEST_CASE(
    "notes are entries of a kind, printed joined by a semicolon, in the order they were made") {
  const auto scene = test::built(parse_scene_text(
      driven_pendulum_scene("scheme = \"baumgarte\"\nconstraints = \"mixed\"\nmax_order = 2\n"),
      "driven.toml"));
  const RunPlan p = plan(scene.model, scene.spec.solve);
  REQUIRE(p.notes.size() == 2);  // set before the run: Baumgarte's gains, the mixed rows
  CHECK(p.notes[0] == RunNote{RunNote::Kind::scheme_setting, p.gains.rule});
  CHECK(p.notes[1].kind == RunNote::Kind::treatment);
  const SolveResult run = test::solved(scene.model, scene.spec.solve);
  REQUIRE(run.summary.notes.size() == 3);
  CHECK(run.summary.notes[2].kind == RunNote::Kind::order_cap);
  CHECK(run.summary.notes_text() ==
        p.gains.rule + "; " + p.notes[1].text + "; " + run.summary.notes[2].text);
  CHECK(run.summary.brief().find("; " + run.summary.notes_text()) != std::string::npos);
}

}  // namespace test_run_plan
