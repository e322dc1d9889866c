// Issue 10, item 2: error weights that fit each kind of unknown. A five-storey shear frame in SI
// units (floor masses 2.5e3–2e4 kg, storey stiffnesses 5e5–1e7 N/m, a base driven by a prescribed
// harmonic displacement, a rigid top floor tying two DOFs) failed to start under index1 at every
// rtol with one scalar atol (IDA_ERR_FAIL at t = 0, h = 5e-15: the multipliers, tens of kN, and
// the velocities were held to the displacements' 1e-10). Each kind now has its own atol, derived
// from the model's scales (dae/formulations/model_scales.hpp) or set in [solve].
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "dae/formulations/model_scales.hpp"
#include "dae/formulations/multiplier_dae.hpp"
#include "dae/run/solve.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/si_shear_frame.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"

using namespace condyn;

namespace test_tolerance_weights {

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();

}  // namespace

TEST_CASE("the same frame in other units: the same motion, forces scaled, about the same steps") {
  // Masses and stiffnesses × 1e-3 (t and kN/m instead of kg and N/m): displacements are the same,
  // multipliers 1e-3 times. The default atol of each kind follows the model's scales, so the error
  // weights are the same numbers and the step counts agree (a factor 1.25 allows for roundoff
  // steering a step decision; with one scalar atol the SI frame did not start at all).
  for (const Scheme scheme : {Scheme::index1, Scheme::ggl, Scheme::index3}) {
    CAPTURE(std::string(to_string(scheme)));
    const test::BuiltScene si = test::si_shear_frame_built(1.0, 1e-8),
                           kn = test::si_shear_frame_built(1e-3, 1e-8);
    const SolveResult r_si = test::solved(si.model, test::under(si.spec.solve, scheme));
    const SolveResult r_kn = test::solved(kn.model, test::under(kn.spec.solve, scheme));
    const SolveSummary &s_si = r_si.summary, &s_kn = r_kn.summary;
    const Trajectory &a = r_si.trajectory, &b = r_kn.trajectory;
    const double ratio = static_cast<double>(std::max(s_si.steps, s_kn.steps)) /
                         static_cast<double>(std::min(s_si.steps, s_kn.steps));
    MESSAGE(std::string(to_string(scheme))
            << ": " << s_si.steps << " steps in SI, " << s_kn.steps << " in kN");
    CHECK(ratio < 1.25);
    // Both runs are within ~40 rtol of the exact motion (case above): 100 rtol apart at most.
    CHECK(relative_error(a, b).displacement < 100 * 1e-8);
    if (scheme == Scheme::index3) continue;  // its λ is out of every test (index 3)
    const double lambda_max = a.multiplier.cwiseAbs().maxCoeff();
    const double diff = (a.multiplier * 1e-3 - b.multiplier).cwiseAbs().maxCoeff();
    CHECK(diff <= 100 * 1e-8 * 1e-3 * lambda_max);
  }
}

TEST_CASE("absolute tolerances per kind: defaults from the model's scales, [solve] keys") {
  const test::BuiltScene scene = test::si_shear_frame_built(1.0, 1e-6);
  const Model& model = scene.model;
  const AbsoluteTolerances a = absolute_tolerances(model, scene.spec.solve);
  const ModelScales s = model_scales(model);
  // T = 1 / ω_min (below t_end = 2 s here); the rule of dae/formulations/model_scales.hpp:
  // velocities atol / t_end (the run, shorter than 1e3 / ω_min), multipliers atol m / T². Closed
  // forms of the same few operations: 8 eps. (With doctest's default Approx, 1e-5 absolute for
  // values this small, the velocity check could not fail and still expected the older atol / T.)
  REQUIRE(s.omega_min > 1.0 / 2.0);
  const double T = 1.0 / s.omega_min;
  CHECK(a.displacement == 1e-10);
  CHECK(a.velocity == doctest::Approx(1e-10 / 2.0).epsilon(8 * kEps));
  CHECK(a.multiplier == doctest::Approx(1e-10 * s.mass / (T * T)).epsilon(8 * kEps));
  CHECK(a.mu == doctest::Approx(a.velocity).epsilon(8 * kEps));  // unit coefficients
  // The mean floor mass (kg): the multipliers' atol is in newtons.
  CHECK(s.mass ==
        doctest::Approx((1e4 + 2e4 + 1.5e4 + 1.2e4 + 8e3 + 2.5e3 + 2.5e3) / 7).epsilon(8 * kEps));

  const test::BuiltScene set = test::si_shear_frame_built(
      1.0, 1e-6, "atol_velocity = 1e-7\natol_multiplier = 1e-3\natol_mu = 2e-9\n");
  const IntegratorSettings o = integrator_settings(set.model, set.spec.solve);
  CHECK(o.atol_of(UnknownKind::displacement) == 1e-10);
  CHECK(o.atol_of(UnknownKind::velocity) == 1e-7);
  CHECK(o.atol_of(UnknownKind::multiplier) == 1e-3);
  CHECK(o.atol_of(UnknownKind::mu) == 2e-9);
  const Eigen::VectorXd v = o.atol_vector(unknown_kinds(2, 1, 1), 6);
  CHECK(v[0] == 1e-10);
  CHECK(v[2] == 1e-7);
  CHECK(v[4] == 1e-3);
  CHECK(v[5] == 2e-9);

  // Derived multiplier tolerances per row: rows more than 1e3 below the largest coefficient
  // get the common figure times how far below they lie ([u u v v | λ λ λ λ | μ]).
  IntegratorSettings per_row = o;
  const std::vector<UnknownKind> kinds = unknown_kinds(2, 4, 1);
  Eigen::VectorXd scales(9);
  scales << 0, 0, 0, 0, 2e9, 2e6, 1.0, 0.0, 1.0;
  const Eigen::VectorXd flat = per_row.atol_vector(kinds, 9, scales);  // the flags are off
  CHECK(flat == per_row.atol_vector(kinds, 9));
  per_row.multiplier_atol_per_row = per_row.mu_atol_per_row = true;
  const Eigen::VectorXd w = per_row.atol_vector(kinds, 9, scales);
  CHECK(w.head(4) == flat.head(4));
  CHECK(w[4] == 1e-3);                                       // the largest row
  CHECK(w[5] == 1e-3);                                       // within 1e3 of it
  CHECK(w[6] == doctest::Approx(1e-3 * 2e6).epsilon(kEps));  // 2e9 / 1e3 / 1
  CHECK(w[7] == 1e-3);                                       // no coefficient: the common one
  CHECK(w[8] == doctest::Approx(2e-9 * 2e6).epsilon(kEps));  // μ of the small row
  // Never past 1e300, where the error weight leaves the normal doubles.
  scales[6] = 1e-300;
  CHECK(per_row.atol_vector(kinds, 9, scales)[6] == 1e300);

  // A huge atol (accepted: the user's unit) derives no infinite one: atol 1e307 made the
  // multipliers' overflow, and the run stopped on 'atol_multiplier must be > 0 and finite'.
  SolveSpec huge = scene.spec.solve;
  huge.atol = 1e307;
  const AbsoluteTolerances h = absolute_tolerances(model, huge);
  CHECK(h.velocity <= 1e300);
  CHECK(h.multiplier == 1e300);
  CHECK(h.mu <= 1e300);
  CHECK_NOTHROW(integrator_settings(model, huge).validate());

  for (const char* key : {"atol_velocity", "atol_multiplier", "atol_mu"}) {
    CAPTURE(std::string(key));
    for (const char* bad : {"0.0", "-1e-6", "nan", "inf", "\"small\""}) {
      CAPTURE(std::string(bad));
      try {
        (void)parse_scene_text(test::si_shear_frame(1.0, std::string(key) + " = " + bad + "\n"),
                               "bad");
        FAIL("accepted");
      } catch (const std::exception& e) {
        CHECK(std::string(e.what()).find(std::string("solve.") + key) != std::string::npos);
      }
    }
  }
}

TEST_CASE("model_scales: a light mass on a heavy one keeps its own frequency") {
  // A double pendulum (rods of 1 m) with 1e6 kg at the knee and 1e-6 kg at the tip: both
  // natural frequencies are √(g/L) = 3.132 to within m2/m1 (linearized about hanging). Released
  // with its rods horizontal, λ(0) = 0 and each rod's tension is estimated from the loads: the
  // tip's rod from the tip's weight, not the knee's 1e6 times larger one (which gave ω = 3.1e6,
  // Baumgarte gains of 3e6 and 2.5 million steps). Hanging and swinging,
  // from λ(0).
  const std::string rods = R"(masses = [0.0, 1e6, 1e-6]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }, { nodes = [2, 3], rigid = true }]
gravity = [0.0, -9.81]
)";
  const double omega = std::sqrt(9.81);
  for (const std::string& start :
       {std::string("nodes = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]\n" + rods),
        std::string("nodes = [[0.0, 0.0], [0.0, -1.0], [0.0, -2.0]]\n" + rods +
                    "[initial]\nvelocity = { ux2 = 0.1, ux3 = 0.2 }\n")}) {
    CAPTURE(start);
    const auto scene = test::built(parse_scene_text(
        "[model]\ntype = \"truss2d\"\n" + start + "[solve]\nt_end = 3.0\noutput_step = 0.1\n",
        "massratio.toml"));
    const ModelScales s = model_scales(scene.model);
    CHECK(s.method == "constrained eigenvalues");
    CHECK(s.omega_min == doctest::Approx(omega).epsilon(0.01));
    CHECK(s.omega_max == doctest::Approx(omega).epsilon(0.01));
  }
}

TEST_CASE("derived multiplier atol per row: a light tip on a heavy body gets its own") {
  // A double pendulum hanging at rest: a 1e6 kg mass on a unit rod from the support, a 1e-6 kg
  // tip on a unit rod below it. The tip's rod carries its weight, λ = m g = 9.81e-6 N; with the
  // mean mass (5e5 kg) every row had atol_multiplier 4.9e-4, fifty times that λ.
  const auto built = test::built(parse_scene_text(R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [0.0, -1.0], [0.0, -2.0]]
masses = [0.0, 1e6, 1e-6]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }, { nodes = [2, 3], rigid = true }]
gravity = [0.0, -9.81]
[solve]
t_end = 1.0
output_step = 0.1
scheme = "ggl"
)",
                                                  "tip.toml"));
  const Model& model = built.model;
  const IntegratorSettings o = integrator_settings(model, built.spec.solve);
  const MultiplierDae dae(*model.system, Scheme::ggl, 0.0, 0.0);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(dae.size());
  const Eigen::VectorXd masses = dae.multiplier_row_masses(0.0, y);
  const Eigen::VectorXd atol =
      o.atol_vector(dae.unknown_kinds(), dae.size(), dae.multiplier_row_scales(0.0, y), masses);
  // y = [u (6) | v (6) | λ: ux1, uy1, the heavy rod, the tip's rod | μ (4)].
  constexpr int kHeavyRod = 14, kTipRod = 15;
  REQUIRE(dae.unknown_kinds()[kTipRod] == UnknownKind::multiplier);
  CHECK(masses[kHeavyRod] == 1e6);  // the support's DOFs are massless
  CHECK(masses[kTipRod] == 1e-6);
  const double common = *o.atol_multiplier, mean = 0.5 * (1e6 + 1e-6);
  CHECK(o.multiplier_mass == doctest::Approx(mean).epsilon(kEps));
  CHECK(atol[kHeavyRod] == common);
  // The tip's row lies 5e11 below the mean, 5e8 beyond the span: its atol is that much smaller.
  CHECK(atol[kTipRod] ==
        doctest::Approx(common * 1e-6 * IntegratorOptions::kRowScaleSpan / mean).epsilon(4 * kEps));
  // And far below the rod's force: atol alone holds λ to at least three digits.
  const double tip_force = 1e-6 * 9.81;
  CHECK(common > tip_force);
  CHECK(atol[kTipRod] < 1e-3 * tip_force);
  // A scene's own atol_multiplier holds for every row.
  SolveSpec given = built.spec.solve;
  given.atol_multiplier = 1e-3;
  const IntegratorSettings g = integrator_settings(model, given);
  CHECK(g.atol_vector(dae.unknown_kinds(), dae.size(), dae.multiplier_row_scales(0.0, y),
                      masses)[kTipRod] == 1e-3);
}

TEST_CASE("derived velocity and μ atols stay above u's roundoff over a step, whatever t_end") {
  // IFToMM A01 (a 1 m pendulum released horizontally, atol 1e-12) over 20 s and over its
  // specification's 2000 s: the velocity and μ atols came from min(t_end, 1e3 / ω_min) alone,
  // 5e-14 at 20 s and 3.1e-15 at 2000 s, below the roundoff eps |u| / h that the BDF derivative
  // passes to v (steps h ~ 1.7e-3 s), and GGL failed at 18.9 s. Both now lie on that floor.
  SceneSpec spec = parse_scene_file(std::string(CONDYN_SOURCE_DIR) +
                                    "/models/scenes/iftomm/A01_simple_pendulum.toml");
  const auto scene = test::built(spec);
  spec.solve.t_end = 20.0;
  const AbsoluteTolerances run_20 = absolute_tolerances(scene.model, spec.solve);
  spec.solve.t_end = 2000.0;
  const AbsoluteTolerances run_2000 = absolute_tolerances(scene.model, spec.solve);
  CHECK(run_2000.velocity == run_20.velocity);
  CHECK(run_2000.mu == run_20.mu);
  CHECK(run_2000.multiplier == run_20.multiplier);
  // Above the roundoff of the speeds the pendulum reaches, √(2 g L) = 4.4 m/s: at an atol_velocity
  // of 1.1e-14 (16 eps of them) GGL still failed at t = 1517 s, at 2.5e-14 it passed.
  const double top_speed = std::sqrt(2.0 * 9.81 * 1.0);
  CHECK(run_2000.velocity > 16.0 * std::numeric_limits<double>::epsilon() * top_speed);
}

}  // namespace test_tolerance_weights
