// Modal damping ratios (issue 13, models/assembly/modal_damping.cpp): damping = { modal = ... }
// gives each mode of the constrained model its ratio, as a C the exact modal reference takes as
// classical.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "models/core/eigen_decompositions.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/exact_solution.hpp"

using namespace condyn;

namespace test_modal_damping {

namespace {

/// A chain ground-a-b-c (springs 400, 200, 100; masses 1, 2, 1), c tied to b by the row
/// c − b = 0 (so two modes remain), a harmonic load on a and an initial velocity.
std::string chain(const std::string& damping) {
  return R"([model]
type = "matrix"
dofs = ["a", "b", "c"]
mass = [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]]
stiffness = [[600.0, -200.0, 0.0], [-200.0, 300.0, -100.0], [0.0, -100.0, 100.0]]
damping = )" +
         damping + R"(
[[load]]
dof = "a"
value = { type = "harmonic", amplitude = 2.0, omega = 5.0 }
[[constraint]]
name = "tie"
terms = { c = 1.0, b = -1.0 }
[initial]
velocity = { a = 0.3 }
[solve]
t_end = 3.0
output_step = 0.1
rtol = 1e-10
atol = 1e-12
)";
}

}  // namespace

TEST_CASE("modal damping: each mode of the constrained model gets its ratio") {
  const auto s = test::built(parse_scene_text(chain("{ modal = [0.02, 0.07] }"), "m.toml"));
  // The constrained modes from their own eigenproblem on the tie's null space, N = [e_a,
  // (e_b + e_c)/√2]: φᵀCφ must be diag(2 z_i ω_i) with φ M-orthonormal.
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(3, 2);
  N(0, 0) = 1.0;
  N(1, 1) = N(2, 1) = 1.0 / std::sqrt(2.0);
  const Eigen::MatrixXd M(s.model.M), K(*s.model.K), C(s.model.C);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(N.transpose() * K * N,
                                                                        N.transpose() * M * N);
  const Eigen::MatrixXd phi = N * modes.eigenvectors();
  const Eigen::MatrixXd modal = phi.transpose() * C * phi;
  const double z[2] = {0.02, 0.07};
  for (int i = 0; i < 2; ++i) {
    const double omega = std::sqrt(modes.eigenvalues()[i]);
    CHECK(modal(i, i) == doctest::Approx(2.0 * z[i] * omega).epsilon(1e-12));
  }
  CHECK(std::abs(modal(0, 1)) <= 1e-12 * modal.cwiseAbs().maxCoeff());
  CHECK(s.report.damping.find("modal damping: ratios 0.02, 0.07") != std::string::npos);
  // A single ratio serves every mode.
  const auto one = test::built(parse_scene_text(chain("{ modal = 0.05 }"), "m.toml"));
  const Eigen::MatrixXd one_modal = phi.transpose() * Eigen::MatrixXd(one.model.C) * phi;
  for (int i = 0; i < 2; ++i) {
    CHECK(one_modal(i, i) ==
          doctest::Approx(2.0 * 0.05 * std::sqrt(modes.eigenvalues()[i])).epsilon(1e-12));
  }
}

TEST_CASE("modal damping: classical, so the exact reference applies, every scheme agrees") {
  const auto s = test::built(parse_scene_text(chain("{ modal = [0.02, 0.07] }"), "m.toml"));
  const Trajectory first =
      test::solved(s.model, test::under(s.spec.solve, Scheme::elimination)).trajectory;
  const Trajectory exact = exact_trajectory(s.model, first.t);  // throws if not classical
  const double peak = exact.u.cwiseAbs().maxCoeff();
  REQUIRE(peak > 1e-3);
  for (Scheme scheme : {Scheme::elimination, Scheme::index1, Scheme::ggl, Scheme::projection}) {
    CAPTURE(std::string(to_string(scheme)));
    const Trajectory d = test::solved(s.model, test::under(s.spec.solve, scheme)).trajectory;
    CHECK((d.u - exact.u).cwiseAbs().maxCoeff() <= 1e-7 * peak);
  }
}

TEST_CASE("modal damping: more ratios than modes are warned of") {
  const auto s =
      test::built(parse_scene_text(chain("{ modal = [0.02, 0.07, 0.1, 0.2] }"), "m.toml"));
  REQUIRE(s.report.warnings.size() == 1);
  CHECK(s.report.warnings[0] ==
        "damping.modal gives 4 ratios for the 2 modes of the constrained model: the last 2 are "
        "unused");
  const auto exact = test::built(parse_scene_text(chain("{ modal = [0.02, 0.07] }"), "m.toml"));
  CHECK(exact.report.warnings.empty());
}

TEST_CASE("modal damping: refusals name the key") {
  const auto refused = [](const std::string& text, const std::string& words) {
    CAPTURE(text);
    CHECK_THROWS_WITH_AS((void)test::built(parse_scene_text(text, "m.toml")),
                         doctest::Contains(words.c_str()), SceneError);
  };
  refused(chain("{ modal = -0.1 }"), "model.damping.modal: a damping ratio must be finite");
  refused(chain("{ modal = [0.02, -0.1] }"), "model.damping.modal[2]: a damping ratio");
  refused(chain("{ modal = [] }"), "model.damping.modal: expected a damping ratio");
  // 5 for 5 %: refused as Rayleigh's ratios are.
  refused(chain("{ modal = 5 }"),
          "model.damping.modal: must be a damping ratio in [0, 1) (0.05 is 5 %)");
  refused(chain("{ modal = [0.02, 1.0] }"),
          "model.damping.modal[2]: must be a damping ratio in [0, 1)");
  refused(chain("{ modal = 0.05, rayleigh = [0.1, 0.0] }"), "not both");
  // A massless DOF has no mode of its own.
  refused(test::replace(chain("{ modal = 0.05 }"), "mass = [[1.0", "mass = [[0.0"),
          "modal damping needs mass on every motion the constraints allow");
}

}  // namespace test_modal_damping
