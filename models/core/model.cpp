// The Model's own member functions.

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "models/core/model.hpp"

namespace condyn {

void Model::index_dofs() {
  dof_order.resize(dof_names.size());
  for (std::size_t i = 0; i < dof_order.size(); ++i) dof_order[i] = static_cast<int>(i);
  std::stable_sort(dof_order.begin(), dof_order.end(), [this](int a, int b) {
    return dof_names[static_cast<std::size_t>(a)] < dof_names[static_cast<std::size_t>(b)];
  });
}

std::optional<int> Model::find_dof(std::string_view dof) const {
  const auto it = std::lower_bound(
      dof_order.begin(), dof_order.end(), dof,
      [this](int i, std::string_view key) { return dof_names[static_cast<std::size_t>(i)] < key; });
  if (it == dof_order.end() || dof_names[static_cast<std::size_t>(*it)] != dof) return {};
  return *it;
}

int Model::dof_at(std::string_view dof) const {
  if (const auto i = find_dof(dof)) return *i;
  throw std::out_of_range("no DOF named '" + std::string(dof) + "'");
}

Eigen::VectorXd Model::absolute_acceleration(double t,
                                             const Eigen::Ref<const Eigen::VectorXd>& a) const {
  if (!ground) return a;
  return a + ground->r * ground->acceleration.derivative(0, t);
}

Eigen::VectorXd Model::derived_values(double t, const Eigen::Ref<const Eigen::VectorXd>& u,
                                      const Eigen::Ref<const Eigen::VectorXd>& v,
                                      const Eigen::Ref<const Eigen::VectorXd>& a,
                                      const Eigen::Ref<const Eigen::VectorXd>& reaction,
                                      const Eigen::Ref<const Eigen::VectorXd>& absolute) const {
  // The absolute acceleration only when a term reads it and the caller has none (an O(n) vector
  // a row), and only from a row that has accelerations: without them derived_value says what
  // the row lacks.
  const Eigen::VectorXd computed =
      absolute.size() == 0 && reads_absolute_acceleration(derived) && a.size() > 0
          ? absolute_acceleration(t, a)
          : Eigen::VectorXd();
  const Eigen::Ref<const Eigen::VectorXd> a_abs =
      absolute.size() > 0 ? absolute : Eigen::Ref<const Eigen::VectorXd>(computed);
  Eigen::VectorXd out(static_cast<Eigen::Index>(derived.size()));
  for (std::size_t k = 0; k < derived.size(); ++k) {
    out[static_cast<Eigen::Index>(k)] = derived_value(derived[k], {u, v, a, a_abs, reaction});
  }
  return out;
}

void add_load_energy(const std::vector<Load>& loads, double t, double steps,
                     const Eigen::Ref<const Eigen::VectorXd>& u,
                     const Eigen::Ref<const Eigen::VectorXd>& v, double& potential, double& power) {
  for (const auto& l : loads) {
    if (l.value.is_constant()) {
      potential -= l.value.derivative(0, t) * l.dot(u);
    } else {
      power += l.value.derivative(0, t, steps) * l.dot(v);
    }
  }
}

Eigen::VectorXd Model::applied_forces(double t, double step_reference) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  for (const auto& l : loads) l.add_to(f, l.value.derivative(0, t, step_reference));
  return f;
}

Eigen::VectorXd Model::applied_forces_derivative(int order, double t) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  for (const auto& l : loads) l.add_to(f, l.value.derivative(order, t));
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

std::vector<double> Model::breakpoints(double t_end) const {
  std::set<double> times;
  for (const auto& l : loads) {
    for (double b : l.value.breakpoints()) {
      if (b < t_end) times.insert(b);
    }
  }
  // A drive's table: its rate jumps at every sample, and with it the velocities the rows fix.
  // The run stops there; the restart moves the velocities onto the rows at the new rate (the
  // least change of kinetic energy: the drive's impulse) and the steps after it see the new
  // segment's slope (TimeTable::slope's one-sided derivative).
  for (const auto& d : drives) {
    for (double b : d.kinks()) {
      if (b > 0.0 && b < t_end) times.insert(b);
    }
  }
  return {times.begin(), times.end()};
}

double Model::first_kink(double t) const {
  double first = std::numeric_limits<double>::infinity();
  // Loads only: a table is refused as a constraint's right-hand side (it needs two derivatives).
  for (const auto& l : loads) first = std::min(first, l.value.first_kink_after(t));
  return first;
}

}  // namespace condyn
