// Mechanisms run through solve(): a planar physical pendulum against its one-DOF equation
// integrated independently, and a spatial pendulum on a spherical joint against its invariants
// (energy, angular momentum about the vertical through the pivot). The Model is made here from
// build_multibody's parts as the scene's builder makes it (models/assembly), without a scene.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "dae/formulations/multiplier_dae.hpp"
#include "dae/run/solve.hpp"
#include "models/core/mechanism.hpp"
#include "models/core/model.hpp"
#include "models/systems/multibody_system.hpp"
#include "tests/compare.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_multibody_runs {

namespace {

constexpr double kGravity = 9.81;
constexpr double kRtol = 1e-10;
/// The global error of a run at rtol over a few swings: up to 1e3 × rtol (the schemes'
/// accuracy per tolerance, as the nonlinear scenes' tests bound it), 1e4 × under index3, which
/// leaves the velocities out of its error test and is the least accurate per tolerance.
double error_bound(Scheme scheme) { return (scheme == Scheme::index3 ? 1e4 : 1e3) * kRtol; }

Model model_of(const MultibodyParts& parts) {
  Model model;
  model.name = "mechanism";
  model.dof_names = parts.coordinate_names;
  model.index_dofs();
  model.system = parts.system;
  model.nonlinear = true;
  model.constraints = parts.rows;
  model.u0 = parts.q0;
  model.v0 = parts.v0;
  const auto s = model.evaluator();
  model.M = s->mass(0.0, model.u0);
  model.K.edit() = s->stiffness(0.0, model.u0, model.v0);
  model.C = s->damping(0.0, model.u0, model.v0);
  model.A = s->constraint_jacobian(0.0, model.u0);
  for (auto* mat : {&model.M, &model.K.edit(), &model.C, &model.A}) mat->prune(0.0);
  return model;
}

SolveSpec settings(Scheme scheme, double t_end) {
  SolveSpec s;
  s.t_end = t_end;
  s.output_step = t_end / 20;
  s.rtol = kRtol;
  s.atol = kRtol;
  s.scheme = scheme;
  return s;
}

Mechanism::Body bar(int dim) {
  Mechanism::Body b;
  b.name = "bar";
  b.mass = 2.0;
  b.inertia = Eigen::Vector3d(0.05, 0.2, 0.17).asDiagonal();
  b.position = {0.6, 0.0, 0.0};
  b.points = {{"end", {-0.6, 0.0, 0.0}}};
  if (dim == 3) {  // turning about the vertical through the hinge: ω × r at the centre
    b.angular_velocity = {0.0, 1.5, 0.0};
    b.velocity = {0.0, 0.0, -0.9};
  }
  return b;
}

/// A bar hinged at its end to the ground's O, released horizontal (2D: revolute, 3D: spherical).
Mechanism pendulum(int dim) {
  Mechanism m;
  m.dimension = dim;
  m.gravity = {0.0, -kGravity, 0.0};
  m.ground_points = {{"O", {0.0, 0.0, 0.0}}};
  m.bodies.push_back(bar(dim));
  Mechanism::Joint hinge;
  hinge.name = "hinge";
  hinge.type = dim == 2 ? Mechanism::JointType::revolute : Mechanism::JointType::spherical;
  hinge.bodies = {Mechanism::kGround, 0};
  m.joints.push_back(hinge);
  return m;
}

/// θ'' = −(m g l / (I + m l²)) cos θ for the bar's angle θ from the horizontal (l its centre's
/// distance from the hinge), by RK4 at a step whose error (h⁴ ≈ 1e-16 per unit time) is far
/// below the runs'.
double reference_angle(double t_end, double m, double inertia, double l) {
  const double k = m * kGravity * l / (inertia + m * l * l);
  const auto rate = [k](const Eigen::Vector2d& y) {
    return Eigen::Vector2d(y[1], -k * std::cos(y[0]));
  };
  Eigen::Vector2d y(0.0, 0.0);
  const int steps = 20000;
  const double h = t_end / steps;
  for (int i = 0; i < steps; ++i) {
    const Eigen::Vector2d k1 = rate(y), k2 = rate(y + 0.5 * h * k1), k3 = rate(y + 0.5 * h * k2),
                          k4 = rate(y + h * k3);
    y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return y[0];
}

}  // namespace

TEST_CASE("multibody run: a planar physical pendulum follows its one-DOF equation") {
  const Mechanism m = pendulum(2);
  const MultibodyParts parts = build_multibody(m);
  const Model model = model_of(parts);
  const double t_end = 2.0;
  const double expected = reference_angle(t_end, 2.0, 0.17, 0.6);
  // auto: GGL with the hinge's rows (linear, constant coefficients) eliminated.
  for (Scheme scheme : {Scheme::index1, Scheme::baumgarte, Scheme::ggl, Scheme::index2,
                        Scheme::index3, Scheme::projection, Scheme::automatic}) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult result = test::solved(model, settings(scheme, t_end));
    const Trajectory& traj = result.trajectory;
    Eigen::VectorXd pose;
    const auto last = static_cast<Eigen::Index>(traj.t.size()) - 1;
    REQUIRE(traj.t.back() == doctest::Approx(t_end));
    parts.outputs->displacement(t_end, traj.u.col(last), Eigen::VectorXd(), pose);
    // The angle (O(1) rad) to the run's global error (observed: index1 1.9e-8, baumgarte
    // 1.3e-9, ggl 2.1e-9, index2 3.7e-9, index3 4.2e-7, projection 1.7e-8, auto 9.9e-10).
    CHECK(std::abs(pose[2] - expected) < error_bound(scheme));
  }
}

TEST_CASE("multibody run: a spatial pendulum keeps its energy and vertical angular momentum") {
  const Mechanism m = pendulum(3);
  const MultibodyParts parts = build_multibody(m);
  const Model model = model_of(parts);
  const auto& b = m.bodies[0];
  // L_y about O: m (r × r')_y + (R I Rᵀ ω)_y, ω = ½ Σ R_k × R_k'.
  const auto momentum = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
    Eigen::Matrix3d R;
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      R.col(k) = q.segment(3 + 3 * k, 3);
      w += 0.5 * Eigen::Vector3d(R.col(k)).cross(Eigen::Vector3d(v.segment(3 + 3 * k, 3)));
    }
    const Eigen::Vector3d r = q.head(3), rv = v.head(3);
    return (b.mass * r.cross(rv) + R * b.inertia * R.transpose() * w)[1];
  };
  const double L0 = momentum(parts.q0, parts.v0);
  REQUIRE(std::abs(L0) > 0.1);  // a precessing start
  for (Scheme scheme : {Scheme::ggl, Scheme::index3, Scheme::projection}) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult result = test::solved(model, settings(scheme, 2.0));
    const Trajectory& traj = result.trajectory;
    double worst = 0.0;
    for (Eigen::Index k = 0; k < traj.u.cols(); ++k)
      worst = std::max(worst, std::abs(momentum(traj.u.col(k), traj.v.col(k)) - L0));
    // Invariants of the exact motion: off by ten times the run's global error relative to
    // their size, since both sum errors of every coordinate (observed: L and E, ggl 2.4e-9 and
    // 4.0e-9, index3 3.2e-6 and 1.5e-6, projection 2.2e-8 and 2.9e-8).
    CHECK(worst < error_bound(scheme) * std::abs(L0) * 10.0);
    CHECK(relative_energy_error(traj) < error_bound(scheme) * 10.0);
  }
}

TEST_CASE("multibody: the multiplier formulations' Jacobians agree with central differences") {
  // A driven spatial revolute chain with every force element: the curvature blocks as the
  // formulations assemble them into Newton's matrix.
  Mechanism m = pendulum(3);
  Mechanism::Body second = bar(3);
  second.name = "second";
  second.position = {1.8, 0.0, 0.0};
  second.points = {{"end", {-0.6, 0.0, 0.0}}, {"tip", {0.6, 0.0, 0.0}}};
  second.axes = {{"z", {0.0, 0.0, 1.0}}};
  m.bodies[0].points.push_back({"tip", {0.6, 0.0, 0.0}});
  m.bodies[0].axes = {{"z", {0.0, 0.0, 1.0}}};
  m.bodies.push_back(second);
  Mechanism::Joint elbow;
  elbow.name = "elbow";
  elbow.type = Mechanism::JointType::revolute;
  elbow.bodies = {0, 1};
  elbow.points = {1, 0};
  elbow.axes = {0, 0};
  TimeTerm wave;
  wave.kind = TimeTerm::Kind::harmonic;
  wave.amplitude = 0.3;
  wave.omega = 2.0;
  elbow.drive = TimeFunction({wave});
  m.joints.push_back(elbow);
  Mechanism::Force spring;
  spring.type = Mechanism::ForceType::spring_damper;
  spring.bodies = {1, Mechanism::kGround};
  spring.points = {1, 0};
  spring.k = 20.0;
  spring.c = 0.5;
  Mechanism::Force rot;
  rot.type = Mechanism::ForceType::rotational_spring_damper;
  rot.joint = 1;
  rot.k = 3.0;
  rot.c = 0.2;
  m.forces = {spring, rot};
  const Model model = model_of(build_multibody(m));
  for (auto scheme :
       {Scheme::index1, Scheme::baumgarte, Scheme::ggl, Scheme::index2, Scheme::index3}) {
    CAPTURE(std::string(to_string(scheme)));
    const MultiplierDae dae(*model.system, scheme, 0.7, 1.3);
    const int n = dae.size();
    Eigen::VectorXd y = 0.05 * Eigen::VectorXd::LinSpaced(n, 0.3, -0.7);
    y.head(model.dofs()) += model.u0;
    const Eigen::VectorXd yp = Eigen::VectorXd::LinSpaced(n, -0.2, 0.9);
    const double t = 0.37, cj = 12.5;
    Eigen::SparseMatrix<double> J = dae.jacobian_pattern().matrix();
    dae.jacobian(t, y, yp, cj, J);
    // As for the nonlinear scenes: central differences with h = 1e-6 are accurate to
    // ~h² |F'''| + eps/h, well inside 1e-6 of the entries.
    CONDYN_CHECK_CLOSE(Eigen::MatrixXd(J), test::finite_difference_jacobian(dae, t, y, yp, cj),
                       1e-6);
  }
}

}  // namespace test_multibody_runs
