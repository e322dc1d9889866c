// A mechanism's start (docs/scenes.md, "Mechanisms of rigid bodies"): the poses and velocities
// of [[body]] checked against the joints and drives at t = 0, each row's residual measured as
// the least change of the poses (velocities) that meets it, within 1e-8 of the model's size; or
// [initial] project = true, keeping what [initial] keep names.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "models/assembly/initial_projection.hpp"
#include "models/assembly/kept_angular_velocity.hpp"
#include "models/assembly/model_builder.hpp"
#include "models/core/mechanism_keep.hpp"

namespace condyn {

namespace {

// Poses and velocities must meet the joints to this fraction of the model's size (the contract's
// "within 1e-8 of the model's size", mechanism_size): hand-written decimals of 10 digits or so
// pass, a pose computed to 6 digits does not.
constexpr double kMechanismConsistency = 1e-8;
constexpr int kMaxReportedColumns = 20;

/// Whether coordinate `name` is a centre of mass' ("crank.rx"), not a direction's.
bool is_position(const std::string& name) {
  const auto dot = name.rfind('.');
  const std::string tail = name.substr(dot + 1);
  return tail == "rx" || tail == "ry" || tail == "rz";
}

}  // namespace

/// Per row, the norm of its gradient with the direction coordinates scaled by the model's size:
/// a row's residual over it is the least change of the centres (and of the points at distance
/// `size` along the directions) that meets the row, to first order. A length for every row.
Eigen::VectorXd ModelBuilder::mechanism_row_gradients(double size) const {
  const Eigen::SparseMatrix<double>& A = model_.A;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(A.rows());
  for (int k = 0; k < A.outerSize(); ++k) {
    const double w = is_position(model_.dof_names[static_cast<std::size_t>(k)]) ? 1.0 : 1.0 / size;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      sum[it.row()] += (it.value() * w) * (it.value() * w);
  }
  return sum.cwiseSqrt();
}

/// The velocities' scale: the fastest point of a body within the model's size, and the drives'
/// rates at t = 0 (an angle's times the size).
double ModelBuilder::mechanism_speed(double size) const {
  const Mechanism& m = *spec_.model.mechanism;
  double speed = 0.0;
  for (const auto& b : m.bodies) {
    speed = std::max(speed, std::hypot(b.velocity[0], b.velocity[1], b.velocity[2]) +
                                size * std::hypot(b.angular_velocity[0], b.angular_velocity[1],
                                                  b.angular_velocity[2]));
  }
  for (const auto& j : m.joints) {
    if (!j.drive) continue;
    const double rate = std::abs(j.drive->derivative(1, 0.0));
    speed = std::max(speed, j.type == Mechanism::JointType::revolute ? size * rate : rate);
  }
  return speed;
}

void ModelBuilder::check_mechanism_start() const {
  const double size = mechanism_size(*spec_.model.mechanism);
  const double speed = mechanism_speed(size);
  const auto s = model_.evaluator();
  const int m = model_.constraint_count();
  Eigen::VectorXd phi(m), psi(m);
  s->position_residual(0.0, model_.u0, phi);
  s->velocity_residual(0.0, model_.u0, model_.v0, psi);
  const Eigen::VectorXd g = mechanism_row_gradients(size);
  const auto least_change = [&](double residual, int i) {
    return residual == 0.0 ? 0.0 : std::abs(residual) / g[i];  // g = 0: infinite, refused
  };
  for (int level = 0; level < 2; ++level) {  // every position row first: velocities need poses
    const double tol = kMechanismConsistency * (level == 0 ? size : speed);
    for (int i = 0; i < m; ++i) {
      const double change = least_change(level == 0 ? phi[i] : psi[i], i);
      if (change <= tol) continue;  // negated below: a NaN is a violation
      const auto& c = model_.constraints[static_cast<std::size_t>(i)];
      const int j = row_joint_[static_cast<std::size_t>(i)];
      const std::string who =
          j >= 0 ? "joint '" + spec_.model.mechanism->joints[static_cast<std::size_t>(j)].name + "'"
                 : "body row '" + c.name + "'";
      std::ostringstream msg;
      msg.precision(3);
      msg << "the initial " << (level == 0 ? "poses violate " : "velocities violate ") << who
          << ": row '" << c.name << "'"
          << (c.nonlinear_kind.empty() ? "" : " (" + c.nonlinear_kind + ")") << " has residual "
          << computed_fmt(level == 0 ? phi[i] : psi[i], "the initial poses and velocities")
          << ", which the " << (level == 0 ? "poses" : "velocities") << " must change by " << change
          << " to meet; allowed: 1e-8 of the model's " << (level == 0 ? "size " : "speed ")
          << (level == 0 ? size : speed)
          << " (docs/scenes.md); fix the [[body]] tables, or set [initial] project = true";
      fail(c.where, msg.str());
    }
  }
}

}  // namespace condyn

namespace condyn {

namespace {

/// The coordinates of body `body` that `kind` names: its centre (rx, ry, rz) or its directions
/// (2D ux, uy; 3D the rotation's columns R11, R21, R31, R12, …, R33).
std::vector<int> body_coordinates(const Model& model, const std::string& body, bool directions,
                                  int dim) {
  std::vector<std::string> names;
  if (!directions) {
    for (const char* c : {"rx", "ry", "rz"}) names.emplace_back(c);
    names.resize(static_cast<std::size_t>(dim));
  } else if (dim == 2) {
    names = {"ux", "uy"};
  } else {
    for (int col = 1; col <= 3; ++col)
      for (int row = 1; row <= 3; ++row)
        names.push_back("R" + std::to_string(row) + std::to_string(col));
  }
  std::vector<int> out;
  out.reserve(names.size());
  for (const auto& n : names) out.push_back(model.dof_at(body + "." + n));
  return out;
}

/// The output columns (displacement, then velocity) of `map` at (u, v).
std::vector<std::pair<std::string, double>> columns(const OutputMap& map, const Eigen::VectorXd& u,
                                                    const Eigen::VectorXd& v) {
  std::vector<std::pair<std::string, double>> out;
  for (const Quantity q : {Quantity::displacement, Quantity::velocity}) {
    const auto& names = map.names(q);
    Eigen::VectorXd values(static_cast<Eigen::Index>(names.size()));
    if (q == Quantity::displacement) {
      map.displacement(0.0, u, Eigen::VectorXd(), values);
    } else {
      map.velocity(0.0, u, v, values);
    }
    for (std::size_t k = 0; k < names.size(); ++k)
      out.emplace_back(names[k], values[static_cast<Eigen::Index>(k)]);
  }
  return out;
}

}  // namespace

/// What the projection moved, in the output's columns (crank.x, crank.angle, crank.omega).
std::string ModelBuilder::mechanism_projection_report(const Eigen::VectorXd& u_in,
                                                      const Eigen::VectorXd& v_in) const {
  const auto before = columns(*model_.outputs, u_in, v_in);
  const auto after = columns(*model_.outputs, model_.u0, model_.v0);
  const double scale =
      std::max(1.0, model_.u0.lpNorm<Eigen::Infinity>() + model_.v0.lpNorm<Eigen::Infinity>());
  const double noise = 64 * std::numeric_limits<double>::epsilon() * scale;
  std::ostringstream s;
  s.precision(10);
  int moved = 0;
  std::ostringstream lines;
  lines.precision(10);
  for (std::size_t k = 0; k < before.size(); ++k) {
    if (!(std::abs(after[k].second - before[k].second) > noise)) continue;
    if (++moved <= kMaxReportedColumns) {
      lines << "\n  " << before[k].first << ": " << before[k].second << " -> " << after[k].second;
    }
  }
  const std::size_t kept = spec_.initial.keep.size();
  if (moved == 0) {
    return "[initial] project = true: the bodies' start already meets the joints; nothing moved";
  }
  s << "projected the bodies' start onto the joints and drives, keeping " << kept << " value"
    << (kept == 1 ? "" : "s") << " of [initial] keep exactly\n  moved " << moved << " value"
    << (moved == 1 ? "" : "s") << " by the least mass-weighted change:" << lines.str();
  if (moved > kMaxReportedColumns) s << "\n  ... and " << moved - kMaxReportedColumns << " more";
  return s.str();
}

void ModelBuilder::project_mechanism() {
  const Mechanism& mech = *spec_.model.mechanism;
  const auto n = static_cast<std::size_t>(model_.dofs());
  std::vector<bool> given_u(n, false), given_v(n, false);
  std::vector<KeptRotationRow> rotations;
  for (const auto& name : spec_.initial.keep) {
    std::string problem;
    for (const KeptValue& k : kept_values(mech, name, problem)) {
      const auto& body = mech.bodies[static_cast<std::size_t>(k.body)];
      switch (k.kind) {
        case KeptValue::Kind::position:
          given_u[static_cast<std::size_t>(model_.dof_at(body.name + ".r" + "xyz"[k.component]))] =
              true;
          break;
        case KeptValue::Kind::orientation:
          for (int d : body_coordinates(model_, body.name, true, mech.dimension))
            given_u[static_cast<std::size_t>(d)] = true;
          break;
        case KeptValue::Kind::velocity:
          given_v[static_cast<std::size_t>(model_.dof_at(body.name + ".r" + "xyz"[k.component]))] =
              true;
          break;
        case KeptValue::Kind::angular_velocity:
          rotations.push_back({body_coordinates(model_, body.name, true, mech.dimension),
                               k.component,
                               body.angular_velocity[static_cast<std::size_t>(k.component)]});
          break;
      }
    }
  }
  std::vector<std::string> names;
  for (const auto& c : model_.constraints) names.push_back(c.name);
  for (const auto& r : rotations) {
    names.push_back("the kept angular velocity, component " + std::string(1, "xyz"[r.component]));
  }
  const auto system = with_kept_rotations(model_.evaluator(), rotations);
  const Eigen::VectorXd u_in = model_.u0, v_in = model_.v0;
  try {
    (void)project_initial_state(*system, 0.0, model_.u0, model_.v0, given_u, given_v,
                                model_.dof_names, names);
  } catch (const InconsistentGivenValues& e) {
    std::string rows;
    for (const auto& [row, residual] : e.violated) {
      rows += (rows.empty() ? "'" : ", '") + names[static_cast<std::size_t>(row)] + "' (residual " +
              fmt(residual) + ")";
    }
    fail({"initial.keep", spec_.initial.where.line},
         "with the values [initial] keep names held exactly, no start meets " + rows +
             ": the kept values are inconsistent with the joints; keep fewer of them");
  } catch (const std::runtime_error& e) {
    fail(spec_.initial.where, e.what());
  }
  report_.initial_projection = mechanism_projection_report(u_in, v_in);
}

}  // namespace condyn
