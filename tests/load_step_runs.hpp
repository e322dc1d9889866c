#pragma once
// Two tied masses under unit step loads at given times, run under every scheme against the closed
// form, with the output rows at exactly the expected times: the cases of test_time_grid.cpp and
// its validation file.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "dae/integrators/step_driver.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

namespace condyn::test::load_steps {

/// Shortest round-trip decimal of x (what a user writes, what a TOML parser reads back as x).
inline std::string literal(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

/// Two unit masses tied by u_a = u_b, springs K = [[2, −1], [−1, 2]], unit step loads on `a` at
/// `starts` (TOML literals, read by the parser as a user's file would be). The sum of the two
/// equations, with q = (u_a + u_b) / 2, is 2 q'' + 2 q = Σ H(t − s_k) whatever the constraint
/// force (so penalty's violation of u_a = u_b leaves q exact too): q(t) = Σ_k (1 − cos(t − s_k)) /
/// 2 over the steps on.
inline std::string scene(const std::vector<std::string>& starts, const std::string& output_step,
                         const std::string& t_end) {
  std::ostringstream s;
  s << "[model]\ntype = \"matrix\"\ndofs = [\"a\", \"b\"]\nmass = [[1.0, 0.0], [0.0, 1.0]]\n"
    << "stiffness = [[2.0, -1.0], [-1.0, 2.0]]\n";
  for (const auto& start : starts) {
    s << "[[load]]\ndof = \"a\"\nvalue = { type = \"step\", start = " << start << " }\n";
  }
  s << "[[constraint]]\nterms = { a = 1.0, b = -1.0 }\n"
    << "[solve]\nt_end = " << t_end << "\noutput_step = " << output_step << "\n";
  return s.str();
}

inline double closed_form(double t, const std::vector<double>& starts) {
  double q = 0.0;
  for (double s : starts) {
    if (t >= s) q += 0.5 * (1.0 - std::cos(t - s));
  }
  return q;
}

/// The rows a run must have: k·h (as Model::output_times computes them) and t_end, each one
/// within roundoff of a load step replaced by that step's time.
inline std::vector<double> expected_rows(double h, double t_end,
                                         const std::vector<double>& starts) {
  const double tol = time_merge_tolerance(0.0, t_end);
  std::vector<double> rows;
  for (long k = 0;; ++k) {
    double t = static_cast<double>(k) * h;
    if (t > t_end - tol) break;  // within roundoff of t_end: t_end itself
    for (double s : starts) {
      if (std::abs(t - s) <= tol) t = s;
    }
    rows.push_back(t);
  }
  rows.push_back(t_end);
  return rows;
}

// Global error of the integrated response against the closed form, for rtol = 1e-8 over a few
// restarts: BDF's global error is a modest multiple of rtol (measured below 2e-7 here, all schemes
// but penalty); 100 rtol leaves room and still fails when a step is missed (an error of order 1e-3
// at least, a step's response over one output interval).
inline constexpr double kRtol = 1e-8;
inline constexpr double kErrorBound = 100 * kRtol;

inline void check_every_scheme(const std::string& text, const std::vector<double>& starts, double h,
                               double t_end) {
  const SceneSpec spec = parse_scene_text(text, "steps.toml");
  const Model model = build_model(spec);
  const std::vector<double> rows = expected_rows(h, t_end, starts);
  for (Scheme scheme : kSchemes) {
    const std::string name = to_string(scheme);
    CAPTURE(name);
    const SolveResult result = solve(model, under(spec.solve, scheme));
    REQUIRE(result.ok());
    const Trajectory& traj = result.trajectory;
    REQUIRE(traj.t.size() == rows.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      CAPTURE(k);
      CHECK(traj.t[k] == rows[k]);  // exactly: the grid's times, not times near them
      const auto col = static_cast<Eigen::Index>(k);
      const double q = 0.5 * (traj.u(0, col) + traj.u(1, col));
      worst = std::max(worst, std::abs(q - closed_form(traj.t[k], starts)));
    }
    CAPTURE(worst);
    CHECK(worst <= kErrorBound);
  }
}

}  // namespace condyn::test::load_steps
