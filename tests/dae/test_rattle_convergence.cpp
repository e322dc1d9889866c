// RATTLE converges at order 2 in the positions and velocities (Hairer, Lubich and Wanner,
// Geometric Numerical Integration, §VII.1.4: a symmetric method of order 2) on a nonlinear
// constrained case, the pendulum on a rigid member, against a tight GGL (BDF) run.

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "models/scene/scene_parser.hpp"
#include "tests/compare.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_rattle_convergence {

namespace {

/// models/scenes/pendulum.toml over 1 s (past the bottom of its first swing), outputs every 0.1 s.
std::string pendulum(const std::string& solve_keys) {
  return test::pendulum_scene("t_end = 1.0\noutput_step = 0.1\n" + solve_keys);
}

}  // namespace

TEST_CASE("rattle on the pendulum: order 2 in displacement and velocity") {
  // The reference: GGL at rtol 1e-12, atol 1e-14 (error about 1e-11, far below RATTLE's
  // smallest, about 1e-5 at h = 1.25e-3); Newton stops at rtol 1e-12, likewise negligible.
  // Order 2 is asserted in [1.8, 2.2], as for the Newmark family; observed: see the message.
  constexpr double kMinOrder = 1.8, kMaxOrder = 2.2;
  const auto ref_scene = test::built(
      parse_scene_text(pendulum("scheme = \"ggl\"\nrtol = 1e-12\natol = 1e-14\n"), "p.toml"));
  const Trajectory reference = test::solved(ref_scene.model, ref_scene.spec.solve).trajectory;
  std::vector<double> log_h, log_u, log_v;
  for (const double h : {1e-2, 5e-3, 2.5e-3, 1.25e-3}) {
    const auto scene =
        test::built(parse_scene_text(pendulum("scheme = \"rattle\"\nstep = " + std::to_string(h) +
                                              "\nrtol = 1e-12\natol = 1e-14\n"),
                                     "p.toml"));
    const Trajectory run = test::solved(scene.model, scene.spec.solve).trajectory;
    REQUIRE(run.t.size() == reference.t.size());
    log_h.push_back(std::log10(h));
    log_u.push_back(std::log10((run.u - reference.u).cwiseAbs().maxCoeff()));
    log_v.push_back(std::log10((run.v - reference.v).cwiseAbs().maxCoeff()));
  }
  const double order_u = test::least_squares_slope(log_h, log_u);
  const double order_v = test::least_squares_slope(log_h, log_v);
  MESSAGE("rattle: observed order " << order_u << " (u), " << order_v
                                    << " (v); smallest error in u "
                                    << std::pow(10.0, log_u.back()));
  CHECK(order_u >= kMinOrder);
  CHECK(order_u <= kMaxOrder);
  CHECK(order_v >= kMinOrder);
  CHECK(order_v <= kMaxOrder);
}

}  // namespace test_rattle_convergence
