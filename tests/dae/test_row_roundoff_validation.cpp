// GGL's μ tolerance and the constraint rows' roundoff (dae/formulations/model_scales.hpp,
// ModelScales:: row_noise): a long hanging chain, whose A Aᵀ amplifies each row's roundoff, runs at
// the derived tolerances; the simple pendulum runs long at tight rtol; and a scene's atol_mu below
// the floor fails with advice that names it.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "dae/formulations/model_scales.hpp"
#include "dae/run/solve.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_row_roundoff_validation {

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

constexpr double kGravity = 9.81;  // tests/scene_text.hpp's chain
constexpr double kLink = 0.5;
constexpr double kDegrees = 30.0;

/// The 30° chain of `links` links, released from rest, over `t_end` with one output interval.
test::BuiltScene chain(int links, double t_end, const std::string& extra = "") {
  const std::string end =
      "t_end = " + std::to_string(t_end) + "\noutput_step = " + std::to_string(t_end) + "\n";
  const std::string text = test::replace(test::hanging_chain_scene(links),
                                         "t_end = 1.0\noutput_step = 0.1\n", end + extra);
  return test::built(parse_scene_text(text, "chain.toml"));
}

}  // namespace

TEST_CASE("a hanging chain of 30,000 links runs under GGL at the derived tolerances") {
  // Before the rows' roundoff floor, atol_mu was atol_v = 1e-10 at t_end = 1 and 1e-7 at
  // t_end = 1e-3; the chain failed with IDA_CONV_FAIL at t = 9.4e-6 and before its first step
  // respectively, and ran with atol_mu = 1e-9 set by hand.
  constexpr int kLinks = 30000;
  constexpr double kEnd = 1e-3;
  const auto scene = chain(kLinks, kEnd);
  const AbsoluteTolerances atol = absolute_tolerances(scene.model, scene.spec.solve);
  CHECK(atol.mu == atol.mu_floor);  // the floor decides here
  CHECK(atol.mu_floor > atol.velocity);
  const SolveResult result = test::solved(scene.model, scene.spec.solve);
  REQUIRE(result.trajectory.t.size() == 2);
  CHECK(result.trajectory.t.back() == kEnd);
  // Reference: every node away from the support moves along the chain's downward normal by
  // g cos 30° t² / 2 (a rigid translation keeps the links' lengths; gravity along the chain is
  // carried by the tension), up to δ² / L, the pull along the chain that the first link's
  // rotation by δ / L needs (3.6e-11 here). Next to the support the tension (1.5e4 N) holds the
  // chain: its transverse wave, √(T / ρ) = 271 m/s, covers 0.27 m by t = 1e-3, within the first
  // link, and the discrete chain's response fades over two more (observed off by 1.0e-7, 1.4e-9,
  // 1.2e-10 at the first three nodes): those are left out. The run's error on top: a few atol
  // (1e-10) over its steps, the error test's absolute tolerance, above rtol |u| (4e-14); 4 atol
  // allowed (observed 1.35e-10 at every node beyond).
  const double angle = kDegrees * std::numbers::pi / 180.0;
  const double fall = 0.5 * kGravity * std::cos(angle) * kEnd * kEnd;
  const Eigen::Vector2d normal(-std::sin(angle), -std::cos(angle));
  const double bound = 4.0 * scene.spec.solve.atol + fall * fall / kLink;
  const Eigen::VectorXd u = result.trajectory.u.col(1);
  double worst = 0.0;
  constexpr int kBoundaryNodes = 3;  // after the support, node 0
  for (int node = 1 + kBoundaryNodes; node <= kLinks; ++node) {
    const Eigen::Vector2d expected = fall * normal;
    worst = std::max(worst, (u.segment<2>(2 * node) - expected).cwiseAbs().maxCoeff());
  }
  MESSAGE("fall " << fall << " m, worst node off by " << worst << " m (bound " << bound << ")");
  CHECK(worst <= bound);
}

TEST_CASE("a scene's atol_mu below the rows' roundoff floor fails with advice naming it") {
  // 3,000 links over 1 s: floor 8.3e-10 (the chain ran at atol_mu = 1e-11 before the floor, with
  // its margin of 16); 1e-12 fails at t = 7.9e-5 (IDA_CONV_FAIL; 1e-13 and below fail before the
  // first step, whose advice is the start's).
  const auto scene = chain(3000, 1.0, "atol_mu = 1e-12\n");
  const SolveResult result = solve(scene.model, scene.spec.solve);
  REQUIRE(result.failure.has_value());
  const std::string& advice = result.failure->suggestion;
  CAPTURE(advice);
  CHECK(contains(advice, "a tolerance asks for more than double precision holds"));
  CHECK(contains(advice, "; atol_mu 1e-12 lies below "));
  CHECK(contains(advice, "remove [solve] atol_mu"));
  CHECK_FALSE(contains(advice, "singular configuration"));
}

TEST_CASE("the pendulum runs hundreds of periods at rtol 1e-10 and 1e-11 under GGL") {
  // The runs collapsed their step at a turning point (t = 1,109 at rtol 1e-10, t = 607 at
  // 1e-11); they ran before the rows' floor too, which leaves the pendulum's tolerances as they
  // were (row_noise about 1e-16): this guards them. The energy error (relative to max(|E(0)|,
  // max kinetic energy) = m g L) grows by an error of order rtol per period: 10 rtol P allowed
  // over P periods (observed 1.0e-8 at 1e-11 over 296 periods, 3.6e-8 at 1e-10 over 507).
  constexpr double kPeriod = 2.368;  // 4 K(1/√2) √(L/g), released with the rod horizontal
  struct Case {
    double rtol, t_end;
  };
  for (const Case c : {Case{1e-11, 700.0}, Case{1e-10, 1200.0}}) {
    CAPTURE(c.rtol);
    SceneSpec spec =
        parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/pendulum.toml");
    spec.solve.rtol = c.rtol;
    spec.solve.t_end = c.t_end;
    spec.solve.output_step = 1.0;
    const Model model = build_model(spec);
    const SolveResult result = test::solved(model, spec.solve);
    CHECK(result.trajectory.t.back() == c.t_end);
    const double error = relative_energy_error(result.trajectory);
    MESSAGE("rtol " << c.rtol << ": relative energy error " << error);
    CHECK(error >= 0.0);
    CHECK(error <= 10.0 * c.rtol * (c.t_end / kPeriod));
  }
}

}  // namespace test_row_roundoff_validation
