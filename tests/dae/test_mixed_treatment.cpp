// The mixed treatment (issue 12, item 7): each constraint row gets its cheapest method
// (dae/formulations/constraint_treatment.hpp), the reduced system keeps the multiplier schemes'
// equations (dae/formulations/eliminated_system.hpp), and results, reactions included, agree with
// the pure formulations and with the chapter's elimination path.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <sstream>
#include <string>

#include "dae/formulations/constraint_treatment.hpp"
#include "dae/formulations/eliminated_system.hpp"
#include "models/scene/scene_parser.hpp"
#include "src/reports/info_report.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"
#include "tests/system_check.hpp"

using namespace condyn;

namespace test_mixed_treatment {

using Reason = ConstraintTreatment::Reason;

namespace {

/// A chain of 30 unit masses joined by springs k = 100 (fixed at neither end), Rayleigh damped,
/// with three kinds of rows: u1 = 0.01 sin(5t) (a prescribed single-freedom row), u10 = u20 (a
/// two-DOF tie) and u21 + ... + u30 = 0 (a ten-DOF average), and a step load on u15.
std::string chain_scene(const std::string& solve_keys) {
  constexpr int n = 30;
  std::ostringstream s;
  s << "[model]\ntype = \"matrix\"\ndofs = [";
  for (int i = 1; i <= n; ++i) s << (i > 1 ? ", " : "") << "\"u" << i << "\"";
  s << "]\nmass = [";
  for (int i = 0; i < n; ++i) {
    s << (i ? ", " : "") << "[";
    for (int j = 0; j < n; ++j) s << (j ? ", " : "") << (i == j ? 1.0 : 0.0);
    s << "]";
  }
  s << "]\nstiffness = [";
  for (int i = 0; i < n; ++i) {
    s << (i ? ", " : "") << "[";
    for (int j = 0; j < n; ++j) {
      const double diag = (i == 0 || i == n - 1) ? 100.0 : 200.0;
      s << (j ? ", " : "") << (i == j ? diag : (std::abs(i - j) == 1 ? -100.0 : 0.0));
    }
    s << "]";
  }
  s << "]\ndamping = { rayleigh = [0.1, 0.001] }\n";
  s << "[[constraint]]\nname = \"ground\"\nterms = { u1 = 1.0 }\n"
       "value = { type = \"harmonic\", amplitude = 0.01, omega = 5.0 }\n";
  s << "[[constraint]]\nname = \"tie\"\nterms = { u10 = 1.0, u20 = -1.0 }\n";
  s << "[[constraint]]\nname = \"average\"\nterms = { ";
  for (int i = 21; i <= n; ++i) s << (i > 21 ? ", " : "") << "u" << i << " = 1.0";
  s << " }\n";
  s << "[[load]]\ndof = \"u15\"\nvalue = { type = \"step\", amplitude = 1.0 }\n";
  s << "[initial]\nvelocity = { u1 = 0.05 }\n";
  s << "[solve]\nt_end = 2.0\noutput_step = 0.1\n" << solve_keys;
  return s.str();
}

double max_abs_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.cols() == b.cols());
  return (a - b).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("treatment per row: supports and ties eliminated, a long MFC keeps its multiplier") {
  const auto scene = test::built(parse_scene_text(chain_scene(""), "chain.toml"));
  const ConstraintTreatment t = treat_constraints(scene.model);
  REQUIRE(t.reason.size() == 3);
  CHECK(t.reason[0] == Reason::single_freedom);
  CHECK(t.reason[1] == Reason::sparse_group);
  CHECK(t.reason[2] == Reason::fills_in);
  // The tie's slave is replaced by one master: no fill. The average's slave (degree 2 or 3 in
  // the chain's K) by nine masters: at least 2 x 8 = 16 entries against its row's 10.
  CHECK(t.fill[1] == 0);
  CHECK(t.group_nonzeros[1] == 2);
  CHECK(t.fill[2] >= 16);
  CHECK(t.group_nonzeros[2] == 10);
  CHECK(t.eliminated == std::vector<int>{0, 1});
  CHECK(t.kept == std::vector<int>{2});
  CHECK(t.transform.T.cols() == 28);
  const std::string report = treatment_report(scene.model, t);
  CHECK(report.find("2 eliminated, 1 with multipliers") != std::string::npos);
  CHECK(report.find("average: multipliers (master-slave would fill in)") != std::string::npos);
}

TEST_CASE("nonlinear rows keep multipliers, their model's linear rows are eliminated") {
  const auto scene = test::built(parse_scene_text(test::driven_pendulum_scene(""), "driven.toml"));
  const ConstraintTreatment t = treat_constraints(scene.model);
  REQUIRE(t.reason.size() == 3);
  CHECK(t.reason[0] == Reason::single_freedom);
  CHECK(t.reason[1] == Reason::single_freedom);
  CHECK(t.reason[2] == Reason::nonlinear);
  CHECK(t.kept == std::vector<int>{2});
}

TEST_CASE("the reduced system's derivatives agree with central differences") {
  // At a state off the constraints' manifold, with the drive's second derivative nonzero (t =
  // 0.4): the rheonomic terms −M G g'' and −A G g'' are in play.
  for (const auto& text : {test::driven_pendulum_scene(""), chain_scene("")}) {
    const auto scene = test::built(parse_scene_text(text, "scene.toml"));
    const EliminatedSystem reduced(scene.model, treat_constraints(scene.model));
    const int n = reduced.dofs(), m = reduced.constraints();
    Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, 0.1, 0.4);
    Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(n, -0.3, 0.2);
    Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(n, 0.5, -0.5);
    Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(m, 1.0, 2.0);
    const auto problems = test::check_system_derivatives(reduced, 0.4, q, w, a, lambda);
    for (const auto& p : problems) INFO(p);
    CHECK(problems.empty());
  }
}

TEST_CASE("mixed treatment under every multiplier scheme agrees with the elimination path") {
  // rtol 1e-10. Displacements are of order 0.09, reactions of order 1.4. The differences
  // observed are below 1.2e-9 (u) and 2.3e-8 (v), the largest under index3, whose
  // positions are the index-3 DAE's (docs/schemes.md, schemes). Reactions and multipliers, from
  // acceleration level at the rows (dae/formulations/row_multipliers.hpp), differ by 5.7e-8 under
  // index3 and at most 3.3e-9 under the others (index3's own λ had differed by 2.1e-6).
  // The bounds leave a margin of 5 to 100.
  const auto scene =
      test::built(parse_scene_text(chain_scene("rtol = 1e-10\natol = 1e-12\n"), "chain.toml"));
  const SolveResult reference =
      test::solved(scene.model, test::under(scene.spec.solve, Scheme::elimination));
  for (Scheme s :
       {Scheme::index1, Scheme::baumgarte, Scheme::ggl, Scheme::index2, Scheme::index3}) {
    const std::string name = to_string(s);
    CAPTURE(name);
    SolveSpec settings = test::under(scene.spec.solve, s);
    settings.treatment = SolveSpec::Treatment::mixed;
    const SolveResult mixed = test::solved(scene.model, settings);
    CHECK(mixed.summary.notes_text().find(
              "mixed treatment: 2 rows eliminated, 1 with multipliers") != std::string::npos);
    const auto& r = reference.trajectory;
    const auto& x = mixed.trajectory;
    CHECK(max_abs_difference(x.u, r.u) < 1e-7);
    CHECK(max_abs_difference(x.v, r.v) < 1e-6);
    CHECK(max_abs_difference(x.reaction, r.reaction) < 5e-7);
    CHECK(max_abs_difference(x.multiplier, r.multiplier) < 5e-7);
    // The eliminated rows hold to roundoff; the kept one to the scheme's tolerance.
    CHECK(mixed.summary.max_drift_position < 1e-9);
  }
}

TEST_CASE("mixed and pure multipliers agree on a nonlinear model with driven linear rows") {
  const auto scene = test::built(
      parse_scene_text(test::driven_pendulum_scene("rtol = 1e-10\natol = 1e-12\n"), "driven.toml"));
  for (Scheme s : {Scheme::index1, Scheme::ggl}) {
    const std::string name = to_string(s);
    CAPTURE(name);
    SolveSpec pure = test::under(scene.spec.solve, s), mixed = pure;
    pure.treatment = SolveSpec::Treatment::multipliers;
    mixed.treatment = SolveSpec::Treatment::mixed;
    const SolveResult a = test::solved(scene.model, pure);
    const SolveResult b = test::solved(scene.model, mixed);
    CHECK(a.summary.notes_text().find("mixed") == std::string::npos);
    CHECK(b.summary.notes_text().find("mixed treatment: 2 rows eliminated, 1 with multipliers") !=
          std::string::npos);
    // Unit rod, g = 9.81: displacements of order 1, reactions up to 28. Both runs approximate the
    // same solution at rtol 1e-10; their differences observed are below 8e-9 (u) and 1.6e-6
    // (reactions, multipliers).
    CHECK(max_abs_difference(a.trajectory.u, b.trajectory.u) < 1e-6);
    CHECK(max_abs_difference(a.trajectory.reaction, b.trajectory.reaction) < 1e-4);
    CHECK(max_abs_difference(a.trajectory.multiplier, b.trajectory.multiplier) < 1e-4);
    // The drive holds exactly under mixed: ux1 is its prescribed value at every output.
    for (std::size_t k = 0; k < b.trajectory.t.size(); ++k) {
      CHECK(b.trajectory.u(0, static_cast<Eigen::Index>(k)) ==
            doctest::Approx(0.1 * std::sin(3.0 * b.trajectory.t[k])).epsilon(1e-14).scale(1.0));
    }
  }
}

TEST_CASE("auto: elimination when every group stays sparse, GGL mixed when one fills in") {
  const auto chain = test::built(parse_scene_text(chain_scene(""), "chain.toml"));
  const SchemeChoice choice = choose_scheme(chain.model, chain.spec.solve);
  CHECK(choice.scheme == Scheme::ggl);
  CHECK(choice.reason.find("2 rows eliminated, 1 kept") != std::string::npos);
  CHECK(uses_mixed_treatment(chain.model, choice.scheme, chain.spec.solve));
  // A scheme named in the scene runs pure unless the scene asks for mixed.
  CHECK_FALSE(
      uses_mixed_treatment(chain.model, Scheme::ggl, test::under(chain.spec.solve, Scheme::ggl)));
  SolveSpec pure = chain.spec.solve;
  pure.treatment = SolveSpec::Treatment::multipliers;
  CHECK_FALSE(uses_mixed_treatment(chain.model, Scheme::ggl, pure));
  // Mixed GGL factors a smaller Newton matrix than pure GGL.
  SolveSpec mixed = test::under(chain.spec.solve, Scheme::ggl);
  mixed.treatment = SolveSpec::Treatment::mixed;
  const SystemSize small = system_size(chain.model, mixed);
  const SystemSize large = system_size(chain.model, test::under(pure, Scheme::ggl));
  CHECK(small.unknowns == 2 * 28 + 2);
  CHECK(large.unknowns == 2 * 30 + 6);
  CHECK(small.jacobian_nonzeros < large.jacobian_nonzeros);
}

TEST_CASE("info names each row's treatment and sizes the mixed systems") {
  const auto chain = test::built(parse_scene_text(chain_scene(""), "chain.toml"));
  std::ostringstream out;
  print_info(out, chain.model, chain.report, chain.spec.solve);
  const std::string text = out.str();
  CHECK(text.find("constraint treatment (mixed): 2 eliminated, 1 with multipliers") !=
        std::string::npos);
  CHECK(text.find("1 eliminated (single-freedom: removes the DOF)") != std::string::npos);
  CHECK(text.find("average: multipliers (master-slave would fill in)") != std::string::npos);
  CHECK(text.find("ggl mixed") != std::string::npos);
}

TEST_CASE("one SchemeDecisions sizes every scheme as system_size does, pure and mixed") {
  const auto chain = test::built(parse_scene_text(chain_scene(""), "chain.toml"));
  SchemeDecisions decisions(chain.model);  // its mixed system built on first use, then shared
  for (const Scheme scheme : {Scheme::index1, Scheme::ggl, Scheme::baumgarte, Scheme::index2,
                              Scheme::index3, Scheme::projection, Scheme::elimination}) {
    for (const auto treatment : {SolveSpec::Treatment::mixed, SolveSpec::Treatment::multipliers}) {
      if (treatment == SolveSpec::Treatment::mixed && !mixes(scheme)) continue;
      CAPTURE(to_string(scheme));
      SolveSpec settings = test::under(chain.spec.solve, scheme);
      settings.treatment = treatment;
      const SystemSize shared = decisions.size(settings),
                       alone = system_size(chain.model, settings);
      CHECK(shared.unknowns == alone.unknowns);
      CHECK(shared.jacobian_nonzeros == alone.jacobian_nonzeros);
      // Two rows eliminated (28 DOFs left), one kept: the mixed systems are the smaller ones.
      if (treatment == SolveSpec::Treatment::mixed) CHECK(shared.unknowns < 2 * 30);
    }
  }
}

TEST_CASE("[solve] constraints: 'mixed' only beside a multiplier scheme or auto") {
  CHECK_THROWS_WITH_AS(
      (void)parse_scene_text(chain_scene("scheme = \"elimination\"\nconstraints = \"mixed\"\n"),
                             "chain.toml"),
      doctest::Contains("solve.constraints: 'mixed' applies to the multiplier schemes"),
      SceneError);
  // 'multipliers' names a treatment of those schemes too: beside penalty it was accepted and
  // meant nothing.
  CHECK_THROWS_WITH_AS(
      (void)parse_scene_text(chain_scene("scheme = \"penalty\"\nconstraints = \"multipliers\"\n"),
                             "chain.toml"),
      doctest::Contains(
          "solve.constraints: 'multipliers' applies to the multiplier schemes (index1, "
          "baumgarte, ggl, index2, index3), the Newmark family (newmark, hht, generalized_alpha) "
          "and auto, not to penalty"),
      SceneError);
  CHECK_THROWS_WITH_AS(
      (void)parse_scene_text(chain_scene("constraints = \"some\"\n"), "chain.toml"),
      doctest::Contains("solve.constraints: expected 'mixed' or 'multipliers'"), SceneError);
  const SceneSpec spec =
      parse_scene_text(chain_scene("scheme = \"index1\"\nconstraints = \"mixed\"\n"), "c.toml");
  CHECK(spec.solve.treatment == SolveSpec::Treatment::mixed);
}

TEST_CASE("the Newmark family mixed: the chain's steps as with a multiplier per row") {
  // A fixed step of 1 ms over the chain's 2 s. With its constant rows eliminated (u = T q + G g)
  // each step solves the pure formulation's equations projected by Tᵀ. At index 3 the pure step
  // holds the driven support's position only, its velocity and acceleration the scheme's, where
  // the reduced one takes g' and g'' themselves: observed 1.4e-10 in u, 1.0e-7 to 2.1e-7 in v,
  // 1.4e-8 to 3.4e-8 in the reactions (displacements of order 0.09, reactions 1.4). Stabilized,
  // the pure step holds the velocity rows too and the two agree to roundoff (5e-14 in u, 4e-13 in
  // v, 1.6e-12 in the reactions). Bounds: ten times the largest.
  const auto scene = test::built(parse_scene_text(chain_scene("step = 1e-3\n"), "chain.toml"));
  for (Scheme s : {Scheme::newmark, Scheme::hht, Scheme::generalized_alpha}) {
    for (const auto form : {NewmarkConstraints::index3, NewmarkConstraints::stabilized}) {
      const std::string name = to_string(s);
      CAPTURE(name);
      CAPTURE(form == NewmarkConstraints::stabilized);
      SolveSpec pure = test::under(scene.spec.solve, s);
      pure.newmark_family.constraints = form;
      SolveSpec mixed = pure;
      pure.treatment = SolveSpec::Treatment::multipliers;
      mixed.treatment = SolveSpec::Treatment::mixed;
      const SolveResult a = test::solved(scene.model, pure);
      const SolveResult b = test::solved(scene.model, mixed);
      CHECK(b.summary.notes_text().find("mixed treatment: 2 rows eliminated, 1 with multipliers") !=
            std::string::npos);
      CHECK(b.summary.unknowns < a.summary.unknowns);
      const bool stabilized = form == NewmarkConstraints::stabilized;
      CHECK(max_abs_difference(b.trajectory.u, a.trajectory.u) < (stabilized ? 5e-13 : 1.5e-9));
      CHECK(max_abs_difference(b.trajectory.v, a.trajectory.v) < (stabilized ? 4e-12 : 2.1e-6));
      CHECK(max_abs_difference(b.trajectory.reaction, a.trajectory.reaction) <
            (stabilized ? 1.6e-11 : 3.4e-7));
      CHECK(b.summary.max_drift_position < 1e-9);
    }
  }
}

}  // namespace test_mixed_treatment
