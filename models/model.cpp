// The Model's own member functions.

#include <algorithm>
#include <cmath>
#include <set>

#include "models/model.hpp"

namespace condyn {

Eigen::VectorXd Model::applied_forces(double t, double step_reference) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  for (const auto& l : loads) f[l.dof] += l.value.derivative(0, t, step_reference);
  return f;
}

Eigen::VectorXd Model::position_rhs(int order, double t) const {
  Eigen::VectorXd g(constraint_count());
  for (int i = 0; i < constraint_count(); ++i) {
    g[i] = constraints[static_cast<std::size_t>(i)].position_value.derivative(order, t);
  }
  return g;
}

bool Model::is_conservative() const {
  if (has_damping()) return false;
  for (const auto& l : loads) {
    if (!l.value.is_constant()) return false;
  }
  for (const auto& c : constraints) {
    if (!c.position_value.is_constant()) return false;
  }
  return true;
}

std::pair<double, double> Model::drift(double t, const Eigen::VectorXd& u,
                                       const Eigen::VectorXd& v) const {
  if (nonlinear) {
    Eigen::VectorXd phi(constraint_count()), psi(constraint_count());
    nonlinear->position_residual(t, u, phi);
    nonlinear->velocity_residual(t, u, v, psi);
    return {phi.size() ? phi.lpNorm<Eigen::Infinity>() : 0.0,
            psi.size() ? psi.lpNorm<Eigen::Infinity>() : 0.0};
  }
  double pos = 0.0, vel = 0.0;
  for (const auto& c : constraints) {
    double au = 0.0, av = 0.0;
    for (const auto& [d, a] : c.coefficients) {
      au += a * u[d];
      av += a * v[d];
    }
    if (c.level == ConstraintSpec::Level::position) {
      pos = std::max(pos, std::abs(au - c.value.value(t)));
      vel = std::max(vel, std::abs(av - c.value.derivative(1, t)));
    } else {
      vel = std::max(vel, std::abs(av - c.value.value(t)));
    }
  }
  return {pos, vel};
}

std::vector<double> Model::breakpoints() const {
  std::set<double> times;
  for (const auto& l : loads) {
    for (double b : l.value.breakpoints()) {
      if (b < solve.t_end) times.insert(b);
    }
  }
  return {times.begin(), times.end()};
}

std::vector<double> Model::output_times() const {
  std::vector<double> times;
  const double h = solve.output_step, t_end = solve.t_end;
  for (long k = 0;; ++k) {
    double t = static_cast<double>(k) * h;
    if (t > t_end - 1e-9 * h) {
      times.push_back(t_end);
      break;
    }
    times.push_back(t);
  }
  return times;
}

}  // namespace condyn
