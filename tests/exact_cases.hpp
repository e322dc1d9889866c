#pragma once
// Every scheme of a list against the exact modal solution
// (validation/references/exact_solution.hpp): the validation scenes under ground motion compare
// runs this one way.

#include <doctest/doctest.h>

#include <initializer_list>
#include <string>

#include "tests/solve_helpers.hpp"
#include "validation/references/exact_solution.hpp"

namespace condyn::test {

/// A scheme and its bounds on the max-norm errors of u and of the reactions, relative to their
/// exact peaks.
struct ExactCase {
  Scheme scheme;
  double u_bound, reaction_bound;
};

/// The exact solution's peaks over all DOFs and outputs.
struct ExactPeaks {
  double u = 0.0, reaction = 0.0;
};

/// Runs the model under each case's scheme with `settings`, checks both errors against the exact
/// solution at the run's output times (computed once, at the first run's times), reports them,
/// and returns the exact peaks for the caller's own checks.
inline ExactPeaks check_against_exact(const Model& model, const SolveSpec& settings,
                                      std::initializer_list<ExactCase> cases) {
  Trajectory exact;
  ExactPeaks peak;
  for (const ExactCase& c : cases) {
    const std::string name = to_string(c.scheme);
    CAPTURE(name);
    const SolveResult run = solved(model, under(settings, c.scheme));
    if (exact.t.empty()) {
      exact = exact_trajectory(model, run.trajectory.t);
      peak.u = exact.u.cwiseAbs().maxCoeff();
      peak.reaction = exact.reaction.cwiseAbs().maxCoeff();
      MESSAGE("peak relative displacement " << peak.u << ", peak reaction " << peak.reaction);
    }
    const double err_u = (run.trajectory.u - exact.u).cwiseAbs().maxCoeff() / peak.u;
    const double err_r =
        (run.trajectory.reaction - exact.reaction).cwiseAbs().maxCoeff() / peak.reaction;
    MESSAGE(name << ": relative error u " << err_u << ", reactions " << err_r << ", "
                 << run.summary.steps << " steps");
    CHECK(err_u < c.u_bound);
    CHECK(err_r < c.reaction_bound);
  }
  return peak;
}

}  // namespace condyn::test
