// validation/references/accuracy.hpp: relative max-norm errors, and the velocity floor that keeps a
// structure at rest from reading an error of 1 against its reference's roundoff velocities.
#include <doctest/doctest.h>

#include <cmath>

#include "validation/references/accuracy.hpp"

using namespace condyn;

namespace test_relative_error {

namespace {

/// One DOF over t = 0 … 2 in 21 rows: u = u(t), v = v(t), no reactions.
template <class U, class V>
Trajectory one_dof(U u, V v) {
  Trajectory tr;
  constexpr int kRows = 21;
  tr.u.resize(1, kRows);
  tr.v.resize(1, kRows);
  tr.reaction = Eigen::MatrixXd::Zero(1, kRows);
  for (int k = 0; k < kRows; ++k) {
    const double t = 0.1 * k;
    tr.t.push_back(t);
    tr.u(0, k) = u(t, k);
    tr.v(0, k) = v(t, k);
  }
  return tr;
}

}  // namespace

TEST_CASE("relative error: a structure at rest is not judged by roundoff velocities") {
  // A static start: u = 0.3 throughout; the reference's velocities are roundoff (±1e-17), the
  // run's exact zeros. Against max |v_ref| alone that read 1; against the floor
  // max |u_ref| / span = 0.3 / 2 it is 1e-17 / 0.15.
  const auto rest = [](double, int) { return 0.3; };
  const Trajectory reference =
      one_dof(rest, [](double, int k) { return (k % 2 ? 1.0 : -1.0) * 1e-17; });
  const Trajectory run = one_dof(rest, [](double, int) { return 0.0; });
  const TrajectoryError err = relative_error(run, reference);
  CHECK(err.displacement == 0.0);
  CHECK(err.velocity == doctest::Approx(1e-17 / 0.15).epsilon(1e-12));
}

TEST_CASE("relative error: a motion's velocities keep their own scale") {
  // u = sin 10t, v = 10 cos 10t over a span of 2: max |v_ref| = 10 is far above the floor
  // max |u_ref| / 2 ≤ 0.5, so a velocity error of 1e-3 reads 1e-4, as before the floor.
  const Trajectory reference = one_dof([](double t, int) { return std::sin(10.0 * t); },
                                       [](double t, int) { return 10.0 * std::cos(10.0 * t); });
  const Trajectory run = one_dof([](double t, int) { return std::sin(10.0 * t); },
                                 [](double t, int) { return 10.0 * std::cos(10.0 * t) + 1e-3; });
  CHECK(relative_error(run, reference).velocity == doctest::Approx(1e-4).epsilon(1e-9));
}

TEST_CASE("relative error: absolute where the reference is identically zero") {
  const auto zero = [](double, int) { return 0.0; };
  const Trajectory reference = one_dof(zero, zero);
  const Trajectory run =
      one_dof([](double, int) { return 2e-9; }, [](double, int) { return 3e-9; });
  const TrajectoryError err = relative_error(run, reference);
  CHECK(err.displacement == doctest::Approx(2e-9));
  CHECK(err.velocity == doctest::Approx(3e-9));
}

TEST_CASE("relative error: reactions near a singular configuration are not scored") {
  // Reactions 2 throughout but at rows 9 and 10, inside a passage: the reference reads 500 there,
  // the run -300 at 10 and 2.001 at 12 (a flagged row in the run only). The undetermined rows
  // neither set the scale nor count: 0.001 / 2 from row 12 alone; unflagged, 800 / 500.
  const auto rest = [](double, int) { return 0.3; };
  Trajectory reference = one_dof(rest, rest);
  Trajectory run = one_dof(rest, rest);
  reference.reaction.setConstant(2.0);
  run.reaction.setConstant(2.0);
  reference.reaction(0, 9) = 500.0;
  reference.reaction(0, 10) = 500.0;
  run.reaction(0, 10) = -300.0;
  run.reaction(0, 11) = 7.0;
  run.reaction(0, 12) = 2.001;
  CHECK(relative_error(run, reference).reaction == doctest::Approx(800.0 / 500.0));
  reference.near_singular.assign(reference.t.size(), false);
  reference.near_singular[9] = reference.near_singular[10] = true;
  run.near_singular.assign(run.t.size(), false);
  run.near_singular[11] = true;
  CHECK(error_scales(reference).reaction == 2.0);
  CHECK(relative_error(run, reference).reaction == doctest::Approx(0.001 / 2.0).epsilon(1e-9));
  // Every row flagged: nothing scored.
  run.near_singular.assign(run.t.size(), true);
  CHECK(relative_error(run, reference).reaction == 0.0);
}

}  // namespace test_relative_error
