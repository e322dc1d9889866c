#pragma once
// The Newmark family's validation runs (issue 45 item 5(d)): a fixed-step second-order method has
// a global error O(h²), not a multiple of rtol, so a case runs at a step h and at h/2 against its
// reference and the observed order, log2 of the errors' ratio, must be 2 in u, u' and the
// reactions (λ at the output rows from acceleration level, as every scheme reports them), and the
// error at h/2 within the accuracy the step was chosen for.

#include <doctest/doctest.h>

#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include "dae/run/scheme_choice.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"

namespace condyn::test {

/// Order 2 asserted as in tests/dae/test_newmark_convergence.cpp: log2(e(h) / e(h/2)) in
/// [1.8, 2.2]; observed values are in each case's message.
constexpr double kMinOrder = 1.8, kMaxOrder = 2.2;
/// The callers choose their steps, a twentieth or less of the shortest period that the response
/// carries, for 1 % relative accuracy at h/2 (the velocities' error, the largest, observed up to
/// 6e-3): a bound on what the chosen step buys, not on the method (which the order check judges).
constexpr double kStepAccuracy = 1e-2;

/// The run of `settings` under `scheme` with the fixed step h.
inline Trajectory at_step(const Model& model, const SolveSpec& settings, Scheme scheme, double h) {
  SolveSpec s = under(settings, scheme);
  s.step = h;
  return solved(model, s).trajectory;
}

/// The observed order of each quantity between two errors (h, then h/2).
inline double order(double coarse, double fine) { return std::log2(coarse / fine); }

/// The Newmark family, and RATTLE where it integrates the model (conservative, scleronomic,
/// constant mass: scheme_refusal).
inline std::vector<Scheme> fixed_step_schemes_for(const Model& model) {
  std::vector<Scheme> schemes;
  for (const Scheme scheme : kFixedStepSchemes) {
    if (newmark_family(scheme) || !scheme_refusal(model, scheme)) schemes.push_back(scheme);
  }
  return schemes;
}

/// Each of `schemes` (default: fixed_step_schemes_for) at h and h/2 against `reference` (same
/// output times): order 2 in displacement, velocity and the reactions, and within kStepAccuracy
/// at h/2.
inline void check_order_two(const std::string& what, const Model& model, const SolveSpec& settings,
                            const Trajectory& reference, double h,
                            const std::vector<Scheme>& given = {}) {
  const std::vector<Scheme> schemes = given.empty() ? fixed_step_schemes_for(model) : given;
  for (const Scheme scheme : schemes) {
    const std::string name = what + " " + to_string(scheme);
    CAPTURE(name);
    const TrajectoryError coarse = relative_error(at_step(model, settings, scheme, h), reference);
    const TrajectoryError fine = relative_error(at_step(model, settings, scheme, h / 2), reference);
    const double orders[] = {order(coarse.displacement, fine.displacement),
                             order(coarse.velocity, fine.velocity),
                             order(coarse.reaction, fine.reaction)};
    MESSAGE(name << ", h = " << h << ": errors u " << coarse.displacement << " -> "
                 << fine.displacement << ", v " << coarse.velocity << " -> " << fine.velocity
                 << ", f_con " << coarse.reaction << " -> " << fine.reaction << "; orders "
                 << orders[0] << ", " << orders[1] << ", " << orders[2]);
    for (int q = 0; q < 3; ++q) {
      CAPTURE(q);
      CHECK(orders[q] >= kMinOrder);
      CHECK(orders[q] <= kMaxOrder);
    }
    CHECK(fine.displacement <= kStepAccuracy);
    CHECK(fine.velocity <= kStepAccuracy);
    CHECK(fine.reaction <= kStepAccuracy);
  }
}

}  // namespace condyn::test
