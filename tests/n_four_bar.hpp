#pragma once
// The IFToMM N-four-bar (A02) for tests of singular passages: its scene with N windows, the crank
// angle of its parallelogram branch in closed form, and a run's largest distance from that branch.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>

#include "dae/run/solve.hpp"
#include "models/core/model.hpp"

namespace condyn::test {

/// The N-four-bar of validation/references/iftomm/write_A02_scene.py (IFToMM A02) with N windows:
/// N+1 upright cranks of 1 m on the ground pivots (i, 0), N horizontal couplers at y = 1, B0
/// moving at +1 m/s along x; bodies of 1 kg and inertia 1/12.
inline std::string n_four_bar(int n) {
  std::ostringstream s;
  s << "[model]\ntype = \"multibody\"\ndimension = 2\ngravity = [0.0, -9.81]\nground = { ";
  for (int i = 0; i <= n; ++i) s << (i ? ", " : "") << "A" << i << " = [" << i << ".0, 0.0]";
  s << " }\n";
  for (int i = 0; i <= n; ++i) {
    s << "[[body]]\nname = \"crank" << i << "\"\nmass = 1.0\ninertia = 0.08333333333333333\n"
      << "position = [" << i << ".0, 0.5]\nangle = 1.5707963267948966\nvelocity = [0.5, 0.0]\n"
      << "angular_velocity = -1.0\npoints = { A = [-0.5, 0.0], B = [0.5, 0.0] }\n";
  }
  for (int i = 1; i <= n; ++i) {
    s << "[[body]]\nname = \"coupler" << i << "\"\nmass = 1.0\ninertia = 0.08333333333333333\n"
      << "position = [" << i - 0.5 << ", 1.0]\nangle = 0.0\nvelocity = [1.0, 0.0]\n"
      << "points = { L = [-0.5, 0.0], R = [0.5, 0.0] }\n";
  }
  const auto joint = [&](const std::string& name, const std::string& a, const std::string& b,
                         const char* pa, const char* pb) {
    s << "[[joint]]\nname = \"" << name << "\"\ntype = \"revolute\"\nbodies = [\"" << a << "\", \""
      << b << "\"]\npoints = [\"" << pa << "\", \"" << pb << "\"]\n";
  };
  for (int i = 0; i <= n; ++i)
    joint("A" + std::to_string(i), "ground", "crank" + std::to_string(i),
          ("A" + std::to_string(i)).c_str(), "A");
  for (int i = 1; i <= n; ++i) {
    const std::string c = "coupler" + std::to_string(i);
    joint("B" + std::to_string(i - 1) + "_L", "crank" + std::to_string(i - 1), c, "B", "L");
    joint("B" + std::to_string(i) + "_R", "crank" + std::to_string(i), c, "B", "R");
  }
  s << "[solve]\nt_end = 5.0\noutput_step = 0.05\n";  // the test sets its own
  return s.str();
}

/// The crank angle φ(t) and φ'(t) on the parallelogram branch (validation/references/iftomm/
/// reference_A02.py): m_eff φ'' = −V cos φ, m_eff = (N+1)/3 + N, V = ((N+1)/2 + N) g (unit
/// masses and lengths), φ(0) = π/2, φ'(0) = −1. Classical Runge-Kutta at h = 1e-4: its error,
/// h⁴ times φ's fifth derivative (of order (V/m_eff)^{5/2} ≈ 1e3) per unit time, is below 1e-12.
struct Branch {
  double phi, rate;
};
inline Branch branch_at(int n, double t) {
  const double m_eff = (n + 1) / 3.0 + n, v = ((n + 1) / 2.0 + n) * 9.81;
  const auto f = [&](const Branch& y) { return Branch{y.rate, -v * std::cos(y.phi) / m_eff}; };
  Branch y{std::numbers::pi / 2.0, -1.0};
  const int steps = static_cast<int>(std::ceil(t / 1e-4));
  const double h = steps > 0 ? t / steps : 0.0;
  for (int k = 0; k < steps; ++k) {
    const Branch k1 = f(y), k2 = f({y.phi + h / 2 * k1.phi, y.rate + h / 2 * k1.rate}),
                 k3 = f({y.phi + h / 2 * k2.phi, y.rate + h / 2 * k2.rate}),
                 k4 = f({y.phi + h * k3.phi, y.rate + h * k3.rate});
    y.phi += h / 6 * (k1.phi + 2 * k2.phi + 2 * k3.phi + k4.phi);
    y.rate += h / 6 * (k1.rate + 2 * k2.rate + 2 * k3.rate + k4.rate);
  }
  return y;
}

/// Over the output rows of `run` (the N-four-bar of n_four_bar(n)): the largest distance of a
/// crank's direction (ux, uy) from (cos φ, sin φ) of the branch and of a coupler's uy from 0, and
/// how many singular passages (sin φ changing sign) the rows span. Leaving the branch is an O(1)
/// error.
inline std::pair<double, int> n_four_bar_error(const Model& model, const Trajectory& run, int n) {
  const auto dof = [&](const std::string& name) {
    return static_cast<Eigen::Index>(model.dof_at(name));  // std::out_of_range when missing
  };
  double worst = 0.0;
  int passages = 0;
  double last_sin = 1.0;
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    const Branch b = branch_at(n, run.t[k]);
    const double c = std::cos(b.phi), s = std::sin(b.phi);
    if (s * last_sin < 0.0) ++passages;
    last_sin = s;
    for (int i = 0; i <= n; ++i) {
      const std::string crank = "crank" + std::to_string(i);
      worst = std::max({worst, std::abs(run.u(dof(crank + ".ux"), col) - c),
                        std::abs(run.u(dof(crank + ".uy"), col) - s)});
    }
    for (int i = 1; i <= n; ++i) {
      worst = std::max(worst, std::abs(run.u(dof("coupler" + std::to_string(i) + ".uy"), col)));
    }
  }
  return {worst, passages};
}

}  // namespace condyn::test
