// solve() returns its result as data: a failed run's kind, facts, suggestion and the rows before
// it; run settings are checked by SolveSpec::validate() before anything runs; one model serves
// runs under different settings.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"

using namespace condyn;

namespace test_solve_result {

TEST_CASE("a failed run is data: kind, time reached, suggestion and the rows before it") {
  // The pulled pendulum cannot go past t = 1 (tests/scene_text.hpp): GGL fails midway.
  const SceneSpec spec = parse_scene_text(test::kPulledPendulumScene, "pulled.toml");
  const Model model = build_model(spec);
  SolveResult result;
  REQUIRE_NOTHROW(result = solve(model, spec.solve));
  REQUIRE_FALSE(result.ok());
  const RunFailure& f = *result.failure;
  CAPTURE(f.message);
  CHECK(result.scheme == Scheme::ggl);
  CHECK(f.in_loop);
  CHECK(f.t0 == 0.0);
  CHECK(f.t_end == 2.0);
  CHECK(f.t_reached > 0.9);  // the motion exists up to t = 1
  CHECK(f.t_reached < 2.0);
  CHECK_FALSE(f.message.empty());
  CHECK_FALSE(f.suggestion.empty());
  // The rows before the failure, assembled like a whole run's: output times up to t_reached.
  const Trajectory& rows = result.trajectory;
  REQUIRE(rows.t.size() >= 2);
  CHECK(rows.t.front() == 0.0);
  CHECK(rows.t.back() <= f.t_reached);
  CHECK(rows.u.cols() == static_cast<Eigen::Index>(rows.t.size()));
  CHECK(rows.multiplier.cols() == static_cast<Eigen::Index>(rows.t.size()));
  // A caller to whom failure is an error gets the message as an exception.
  CHECK_THROWS_WITH_AS((void)succeeded(result), f.message.c_str(), std::runtime_error);
}

TEST_CASE("run settings are validated before a run, naming the key") {
  const SceneSpec spec = parse_scene_text(test::kTwoMassesScene, "two.toml");
  const Model model = build_model(spec);
  const auto refusal = [&](void (*change)(SolveSpec&)) {
    SolveSpec s = spec.solve;
    change(s);
    try {
      (void)solve(model, s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK(refusal([](SolveSpec& s) { s.rtol = 0.0; }).find("solve.rtol") == 0);
  CHECK(refusal([](SolveSpec& s) { s.rtol = 1.0; }).find("solve.rtol") == 0);
  CHECK(refusal([](SolveSpec& s) { s.atol = 1e-300; }).find("solve.atol") == 0);
  CHECK(refusal([](SolveSpec& s) { s.atol_mu = -1.0; }).find("solve.atol_mu") == 0);
  CHECK(refusal([](SolveSpec& s) { s.t_end = -1.0; }).find("solve.t_end") == 0);
  CHECK(refusal([](SolveSpec& s) {
          s.output_step = std::numeric_limits<double>::quiet_NaN();
        }).find("solve.output_step") == 0);
  CHECK(refusal([](SolveSpec& s) { s.penalty_weight = 0.0; }).find("solve.penalty.weight") == 0);
  CHECK(refusal([](SolveSpec& s) { s.max_steps = -5; }).find("solve.max_steps") == 0);
  CHECK(refusal([](SolveSpec& s) { s.max_wall_time = INFINITY; }).find("solve.max_wall_time") == 0);
  CHECK(refusal([](SolveSpec& s) {
          s.max_steps_per_output = -1;
        }).find("solve.max_steps_per_output") == 0);
  CHECK(refusal([](SolveSpec&) {}) == "accepted");
}

TEST_CASE("one model, many settings: a tolerance sweep on one build matches fresh builds") {
  // compare runs every tolerance on the model it built once; the settings are the only input that
  // changes, so a run on the shared model equals a run on a model built with those settings.
  SceneSpec spec = parse_scene_text(test::kTwoMassesScene, "two.toml");
  const Model shared = build_model(spec);
  for (const double rtol : {1e-4, 1e-8}) {
    CAPTURE(rtol);
    spec.solve.rtol = rtol;
    spec.solve.atol = rtol * 1e-2;
    for (const Scheme scheme : {Scheme::elimination, Scheme::ggl}) {
      CAPTURE(std::string(to_string(scheme)));
      const SolveSpec settings = test::under(spec.solve, scheme);
      const SolveResult a = test::solved(shared, settings);
      const SolveResult b = test::solved(build_model(spec), settings);
      CHECK(a.summary.steps == b.summary.steps);
      CHECK(a.trajectory.u == b.trajectory.u);  // deterministic: bit for bit
    }
  }
}

TEST_CASE("one nonlinear model, two threads: each run evaluates its own system") {
  // The Model holds its system as a constant prototype and every run evaluates a clone, so runs
  // on one model in parallel threads give what each gives alone (bit for bit: same operations).
  // Before, the nonlinear systems' scratch matrices were shared `mutable` members.
  const SceneSpec spec = parse_scene_text(
      test::pendulum_scene("t_end = 2.0\noutput_step = 0.1\nrtol = 1e-8\n"), "pendulum.toml");
  const Model model = build_model(spec);
  REQUIRE(model.is_nonlinear());
  const SolveSpec ggl = test::under(spec.solve, Scheme::ggl);
  const SolveSpec projection = test::under(spec.solve, Scheme::projection);
  const Trajectory alone_ggl = test::solved(model, ggl).trajectory;
  const Trajectory alone_projection = test::solved(model, projection).trajectory;
  SolveResult a, b;
  std::thread first([&] { a = solve(model, ggl); });
  std::thread second([&] { b = solve(model, projection); });
  first.join();
  second.join();
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(a.trajectory.u == alone_ggl.u);
  CHECK(b.trajectory.u == alone_projection.u);
}

TEST_CASE("the run summary prints its wall time without an exponent") {
  SolveSummary s;
  s.scheme = "ggl";
  const auto wall = [&s](double seconds) {
    s.wall_seconds = seconds;
    const std::string line = s.brief();
    const auto at = line.find(", wall ");
    REQUIRE(at != std::string::npos);
    return line.substr(at + 7, line.find(" ms", at) - at - 7);
  };
  CHECK(wall(0.00184) == "1.84");
  CHECK(wall(0.0758) == "75.8");
  CHECK(wall(0.7584) == "758");
  // Four minutes: every millisecond shown (it was "2.5e+05").
  CHECK(wall(250.1234) == "250123");
}

TEST_CASE("the budget of steps between two outputs: given, default, or the run's own budget") {
  SolveSpec s;
  CHECK(s.steps_per_output_budget() == kDefaultStepsPerOutput);
  s.max_steps = 500;  // below the default: the run's budget ends the run first anyway
  CHECK(s.steps_per_output_budget() == kDefaultStepsPerOutput);
  s.max_steps = 3 * kDefaultStepsPerOutput;  // above: no smaller hidden cap cuts in before it
  CHECK(s.steps_per_output_budget() == 3 * kDefaultStepsPerOutput);
  s.max_steps_per_output = 7;  // given: as given
  CHECK(s.steps_per_output_budget() == 7);
}

}  // namespace test_solve_result
