// The projection scheme's sparse Newton solve (dae/formulations/kkt_newton.hpp) against the dense
// Newton matrix I − γ J, with J = ∂F/∂y of the projected ODE by central differences.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>

#include "dae/formulations/kkt_newton.hpp"
#include "dae/formulations/projected_ode.hpp"
#include "dae/linsolve/kkt.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_kkt_newton {

TEST_CASE("the sparse saddle-point solve is the Newton matrix I - gamma J of the projected ODE") {
  // The chapter's truss with damping and an MFC (validation scene 5.6.1) and Rayleigh damping.
  std::string text = R"(
[model]
type = "matrix"
dofs = ["u1", "u2", "u3", "u4"]
mass = [[2.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.5, 0.2], [0, 0, 0.2, 1.0]]
stiffness = [[3.0, -1.0, 0, 0], [-1.0, 2.0, -1.0, 0], [0, -1.0, 2.0, -1.0], [0, 0, -1.0, 1.0]]
damping = { rayleigh = [0.1, 0.02] }
[[constraint]]
terms = { u1 = 1.0, u3 = -0.5 }
[[load]]
dof = "u4"
value = { type = "step", amplitude = 1.0 }
[solve]
t_end = 1.0
output_step = 0.1
)";
  const auto scene = test::built(parse_scene_text(text, "kkt.toml"));
  const Model& model = scene.model;
  const ProjectedOde ode(*model.system, model.u0, true);
  const auto newton = ode.newton_system();
  REQUIRE(newton != nullptr);
  const int N = ode.size();
  // J by central differences at a state off the manifold (the right-hand side is affine in y:
  // the differences are exact up to roundoff, relative 1e-10 with this step).
  Eigen::VectorXd y(N);
  for (int i = 0; i < N; ++i) y[i] = 0.1 * std::sin(1.3 * i + 0.4);
  Eigen::MatrixXd J(N, N);
  constexpr double h = 1e-3;
  for (int j = 0; j < N; ++j) {
    Eigen::VectorXd yp = y, ym = y, fp(N), fm(N);
    yp[j] += h;
    ym[j] -= h;
    ode.rhs(0.5, yp, fp);
    ode.rhs(0.5, ym, fm);
    J.col(j) = (fp - fm) / (2.0 * h);
  }
  for (const double gamma : {1e-4, 1e-2, 0.3}) {
    CAPTURE(gamma);
    REQUIRE(newton->setup(gamma));
    const Eigen::MatrixXd matrix = Eigen::MatrixXd::Identity(N, N) - gamma * J;
    Eigen::VectorXd b(N);
    for (int i = 0; i < N; ++i) b[i] = std::cos(0.7 * i) - 0.3;
    const Eigen::VectorXd expected = matrix.fullPivLu().solve(b);
    Eigen::VectorXd x = b;
    newton->solve(x);
    // Condition of I − γJ here is below 1e3; the differences carry 1e-10: 1e-8 relative.
    CHECK((x - expected).norm() <= 1e-8 * expected.norm());
  }
}

TEST_CASE("kkt_matrix: [M Aᵀ | A 0] entry by entry, stored zeros kept, no rows, uncompressed M") {
  Eigen::MatrixXd Md(3, 3), Ad(2, 3);
  Md << 2, 0, 0.5, 0, 1, 0, 0.5, 0, 3;
  Ad << 1, 0, -1, 0, 2, 0;
  Eigen::SparseMatrix<double> M = Md.sparseView(), A = Ad.sparseView();
  M.coeffRef(1, 0) = 0.0;  // a stored zero: part of the pattern, as MechanicalSystem's contract
  M.makeCompressed();
  const Eigen::SparseMatrix<double> K = kkt_matrix(M, A);
  REQUIRE(K.isCompressed());
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(5, 5);
  expected.topLeftCorner(3, 3) = Md;
  expected.bottomLeftCorner(2, 3) = Ad;
  expected.topRightCorner(3, 2) = Ad.transpose();
  CHECK(Eigen::MatrixXd(K) == expected);
  CHECK(K.nonZeros() == M.nonZeros() + 2 * A.nonZeros());  // the stored zero included
  // Without rows: M itself; an uncompressed M (inserted entries) gives the same matrix.
  CHECK(Eigen::MatrixXd(kkt_matrix(M, Eigen::SparseMatrix<double>(0, 3))) == Md);
  Eigen::SparseMatrix<double> loose(3, 3);
  loose.insert(2, 2) = 3.0;
  loose.insert(0, 0) = 2.0;
  REQUIRE_FALSE(loose.isCompressed());
  const Eigen::SparseMatrix<double> K2 = kkt_matrix(loose, A);
  CHECK(K2.coeff(2, 2) == 3.0);
  CHECK(K2.coeff(4, 1) == 2.0);
  CHECK(K2.coeff(0, 3) == 1.0);
  CHECK(K2.nonZeros() == 2 + 2 * A.nonZeros());
}

namespace {

/// ∂F/∂y of the projected ODE at (t, y) by central differences with steps h (|y_j| + 1).
Eigen::MatrixXd projected_ode_jacobian(const ProjectedOde& ode, double t, const Eigen::VectorXd& y,
                                       double h) {
  const int N = ode.size();
  Eigen::MatrixXd J(N, N);
  for (int j = 0; j < N; ++j) {
    const double step = h * (std::abs(y[j]) + 1.0);
    Eigen::VectorXd yp = y, ym = y, fp(N), fm(N);
    yp[j] += step;
    ym[j] -= step;
    ode.rhs(t, yp, fp);
    ode.rhs(t, ym, fm);
    J.col(j) = (fp - fm) / (2.0 * step);
  }
  return J;
}

}  // namespace

TEST_CASE("nonlinear models: the saddle-point solve is I - gamma J at the state it linearises at") {
  // Point masses on rigid bars (the hanging chain, a slider-crank), elastic members with large
  // rotations (von Mises), a pre-stressed spring with a dashpot beside a rigid bar (damping and
  // tangent stiffness), the rows a redundant bar leaves (redundant = "drop"), generalized
  // coordinates with a state-dependent M (Andrews), and a nonholonomic row whose γ depends on
  // the velocities (the sleigh): every curvature block.
  for (const char* name :
       {"hanging_chain", "slider_crank", "von_mises_truss", "damped_spring_pendulum",
        "parallelogram_redundant_bar", "andrews", "chaplygin_sleigh", "car_axis"}) {
    CAPTURE(std::string(name));
    const auto scene = test::built(
        parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/" + name + ".toml"));
    const Model& model = scene.model;
    REQUIRE(model.nonlinear);
    ProjectedOde ode(*model.system, model.u0, false);
    ode.begin_segment(0.0);
    const auto newton = ode.newton_system();
    REQUIRE(newton != nullptr);
    REQUIRE(newton->state_dependent());
    const int N = ode.size();
    // A state near the initial one, moved in every component (off the manifold, where the
    // Newton iterations evaluate too) by a few percent of the state's size.
    Eigen::VectorXd y(N);
    y << model.u0, model.v0;
    const double size = y.lpNorm<Eigen::Infinity>() + 1.0;
    for (int i = 0; i < N; ++i) y[i] += 0.01 * size * std::sin(1.3 * i + 0.4);
    const double t = 0.05;
    newton->linearize_at(t, y);
    // Central differences with steps 1e-5 (|y_j| + 1): truncation O(h²) and roundoff
    // eps |F| / h, both below kDifferenceError of ‖J‖ on these models.
    constexpr double kDifferenceError = 1e-6;
    const Eigen::MatrixXd J = projected_ode_jacobian(ode, t, y, 1e-5);
    for (const double gamma : {1e-4, 1e-2, 0.1}) {
      CAPTURE(gamma);
      REQUIRE(newton->setup(gamma));
      Eigen::VectorXd b(N);
      for (int i = 0; i < N; ++i) b[i] = std::cos(0.7 * i) - 0.3;
      Eigen::VectorXd x = b;
      newton->solve(x);
      // (I − γ J_fd) x − b = −γ δJ x for the differences' error δJ: bounded by
      // γ kDifferenceError ‖J‖ ‖x‖ (a missing curvature block leaves γ ‖block‖ ‖x‖ or more).
      const Eigen::VectorXd residual = x - gamma * (J * x) - b;
      const double bound = gamma * kDifferenceError * J.norm() * x.norm();
      CAPTURE(residual.norm());
      CAPTURE(bound);
      CHECK(residual.norm() <= bound);
    }
  }
}

}  // namespace test_kkt_newton
