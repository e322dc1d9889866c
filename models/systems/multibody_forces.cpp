#include "models/systems/multibody_forces.hpp"

#include <cmath>
#include <set>

#include "models/systems/multibody_rows.hpp"

namespace condyn {

namespace {

using ForceType = Mechanism::ForceType;

/// The columns a vector touches, ascending.
std::vector<int> columns_of(const AffineVector& x) {
  std::set<int> cols;
  for (const auto& row : x.coefficients)
    for (const auto& entry : row) cols.insert(entry.first);
  return {cols.begin(), cols.end()};
}

int local_index(const std::vector<int>& cols, int col) {
  return static_cast<int>(std::lower_bound(cols.begin(), cols.end(), col) - cols.begin());
}

}  // namespace

MultibodyForces::MultibodyForces(const Mechanism& m, const MultibodyGeometry& g)
    : dim_(m.dimension), n_(g.coordinates()), geometry_(g) {
  for (int r = 0; r < dim_; ++r) {  // gravity: one constant pattern load per direction
    const double gr = m.gravity[static_cast<std::size_t>(r)];
    if (gr == 0.0 || m.bodies.empty()) continue;
    Load load;
    load.dof = -1;
    load.value = TimeFunction::constant(gr);
    load.pattern.resize(n_);
    for (std::size_t b = 0; b < m.bodies.size(); ++b)
      load.pattern.insert(g.offset(static_cast<int>(b)) + r) = m.bodies[b].mass;
    loads_.push_back(std::move(load));
  }
  const Eigen::VectorXd q0 = g.initial_coordinates(m);
  for (const auto& f : m.forces) {
    switch (f.type) {
      case ForceType::spring_damper:
        add_spring(m, q0, f);
        break;
      case ForceType::rotational_spring_damper:
        add_angle(m, q0, f);
        break;
      case ForceType::point_force:
        add_point_force(g, m, f);
        break;
      case ForceType::torque:
        torques_.push_back({f.bodies[0], f.components});
        conservative_ = false;
        break;
    }
    if (f.c != 0.0) conservative_ = false;
  }
  for (const auto& l : loads_) conservative_ = conservative_ && l.value.is_constant();
}

void MultibodyForces::add_spring(const Mechanism& m, const Eigen::VectorXd& q0,
                                 const Mechanism::Force& f) {
  const MultibodyGeometry& g = geometry_;
  const AffineVector x1 = g.point(f.bodies[0], g.marker(m, f.bodies[0], f.points[0]));
  const AffineVector x2 = g.point(f.bodies[1], g.marker(m, f.bodies[1], f.points[1]));
  const AffineVector d = x2 - x1;
  LocalVector local{columns_of(d), Eigen::MatrixXd::Zero(dim_, 0), d.constant};
  local.B = Eigen::MatrixXd::Zero(dim_, static_cast<Eigen::Index>(local.cols.size()));
  for (int r = 0; r < dim_; ++r) {
    for (const auto& [col, value] : d.coefficients[static_cast<std::size_t>(r)])
      local.B(r, local_index(local.cols, col)) = value;
  }
  const double rest = f.rest_length ? *f.rest_length : d.value(q0).norm();
  springs_.push_back({std::move(local), f.k, f.c, rest});
}

void MultibodyForces::add_angle(const Mechanism& m, const Eigen::VectorXd& q0,
                                const Mechanism::Force& f) {
  const RelativeAngle angle = relative_angle(m, geometry_, q0, f.joint);
  // The deflection δ = θ − θ_rest: X = cos δ = x cos θ_r + y sin θ_r, Y = sin δ = y cos θ_r −
  // x sin θ_r (x = cos θ, y = sin θ).
  const double cr = std::cos(f.rest_angle), sr = std::sin(f.rest_angle);
  QuadraticForm X = angle.x.scaled(cr), Y = angle.y.scaled(cr);
  X += angle.y.scaled(sr);
  Y += angle.x.scaled(-sr);
  std::set<int> support;
  for (const auto* form : {&X, &Y}) {
    for (const auto& entry : form->H) support.insert(entry.first.first);
    for (const auto& entry : form->g) support.insert(entry.first);
  }
  Angle a;
  a.cols.assign(support.begin(), support.end());
  const auto size = static_cast<Eigen::Index>(a.cols.size());
  const auto local = [&](const QuadraticForm& form, Eigen::MatrixXd& H, Eigen::VectorXd& gv) {
    H = Eigen::MatrixXd::Zero(size, size);
    gv = Eigen::VectorXd::Zero(size);
    for (const auto& [at, value] : form.H)
      H(local_index(a.cols, at.first), local_index(a.cols, at.second)) += value;
    for (const auto& [col, value] : form.g) gv[local_index(a.cols, col)] += value;
  };
  local(X, a.HX, a.gX);
  local(Y, a.HY, a.gY);
  a.cX = X.c;
  a.cY = Y.c;
  a.k = f.k;
  a.c = f.c;
  angles_.push_back(std::move(a));
}

void MultibodyForces::add_point_force(const MultibodyGeometry& g, const Mechanism& m,
                                      const Mechanism::Force& f) {
  const AffineVector x = g.point(f.bodies[0], g.marker(m, f.bodies[0], f.points[0]));
  for (int r = 0; r < dim_ && r < static_cast<int>(f.components.size()); ++r) {
    Load load;
    load.dof = -1;
    load.value = f.components[static_cast<std::size_t>(r)];
    load.pattern.resize(n_);
    for (const auto& [col, value] : x.coefficients[static_cast<std::size_t>(r)])
      load.pattern.coeffRef(col) += value;
    loads_.push_back(std::move(load));
  }
}

Eigen::VectorXd MultibodyForces::gather(const std::vector<int>& cols, const ConstRef& x) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(cols.size()));
  for (std::size_t i = 0; i < cols.size(); ++i) out[static_cast<Eigen::Index>(i)] = x[cols[i]];
  return out;
}

void MultibodyForces::scatter(const std::vector<int>& cols, const Eigen::MatrixXd& block,
                              Triplets& out) {
  for (std::size_t i = 0; i < cols.size(); ++i) {
    for (std::size_t j = 0; j < cols.size(); ++j) {
      out.emplace_back(cols[i], cols[j],
                       block(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
    }
  }
}

MultibodyForces::AngleState MultibodyForces::angle_state(const Angle& a, const ConstRef& q) const {
  const Eigen::VectorXd ql = gather(a.cols, q);
  const Eigen::VectorXd dX = a.HX * ql + a.gX, dY = a.HY * ql + a.gY;
  const double X = 0.5 * ql.dot(a.HX * ql) + a.gX.dot(ql) + a.cX;
  const double Y = 0.5 * ql.dot(a.HY * ql) + a.gY.dot(ql) + a.cY;
  const double rho2 = X * X + Y * Y;
  AngleState s;
  s.delta = std::atan2(Y, X);
  if (rho2 == 0.0) {  // no frame to measure against (q = 0, where patterns are taken): no force
    s.grad = Eigen::VectorXd::Zero(ql.size());
    s.hess = Eigen::MatrixXd::Zero(ql.size(), ql.size());
    return s;
  }
  s.grad = (X * dY - Y * dX) / rho2;
  s.hess = (dY * dX.transpose() - dX * dY.transpose() + X * a.HY - Y * a.HX) / rho2 -
           s.grad * (2.0 * X * dX + 2.0 * Y * dY).transpose() / rho2;
  return s;
}

void MultibodyForces::add_torque(const Torque& tq, double t, double steps, const ConstRef& q,
                                 Ref f) const {
  const int o = geometry_.offset(tq.body);
  if (dim_ == 2) {  // τ perp(u) on u
    const double tau = tq.components.at(0).derivative(0, t, steps);
    f[o + 2] -= tau * q[o + 3];
    f[o + 3] += tau * q[o + 2];
    return;
  }
  Eigen::Vector3d T;
  for (int r = 0; r < 3; ++r)
    T[r] = tq.components.at(static_cast<std::size_t>(r)).derivative(0, t, steps);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d Rk = q.segment(o + 3 + 3 * k, 3);
    f.segment(o + 3 + 3 * k, 3) += 0.5 * T.cross(Rk);
  }
}

void MultibodyForces::add_force(double t, double steps, const ConstRef& q, const ConstRef& v,
                                Ref f) const {
  for (const auto& l : loads_) l.add_to(f, l.value.derivative(0, t, steps));
  for (const auto& tq : torques_) add_torque(tq, t, steps, q, f);
  for (const auto& s : springs_) {
    const Eigen::VectorXd d = s.d.B * gather(s.d.cols, q) + s.d.x0;
    const double l = d.norm();
    if (l == 0.0) continue;  // no direction
    const Eigen::VectorXd e = d / l;
    const double rate = e.dot(s.d.B * gather(s.d.cols, v));
    const Eigen::VectorXd fl = s.d.B.transpose() * (-(s.k * (l - s.rest) + s.c * rate) * e);
    for (std::size_t i = 0; i < s.d.cols.size(); ++i)
      f[s.d.cols[i]] += fl[static_cast<Eigen::Index>(i)];
  }
  for (const auto& a : angles_) {
    const AngleState st = angle_state(a, q);
    const double moment = -a.k * st.delta - a.c * st.grad.dot(gather(a.cols, v));
    for (std::size_t i = 0; i < a.cols.size(); ++i)
      f[a.cols[i]] += moment * st.grad[static_cast<Eigen::Index>(i)];
  }
}

void MultibodyForces::stiffness(double t, double steps, const ConstRef& q, const ConstRef& v,
                                Triplets& out) const {
  for (const auto& tq : torques_) {
    const int o = geometry_.offset(tq.body);
    if (dim_ == 2) {  // −∂(τ perp(u))/∂u
      const double tau = tq.components.at(0).derivative(0, t, steps);
      out.emplace_back(o + 2, o + 3, tau);
      out.emplace_back(o + 3, o + 2, -tau);
      continue;
    }
    Eigen::Vector3d T;
    for (int r = 0; r < 3; ++r)
      T[r] = tq.components.at(static_cast<std::size_t>(r)).derivative(0, t, steps);
    for (int k = 0; k < 3; ++k) {  // −½ [T]×
      const int c = o + 3 + 3 * k;
      out.emplace_back(c + 0, c + 1, 0.5 * T[2]);
      out.emplace_back(c + 0, c + 2, -0.5 * T[1]);
      out.emplace_back(c + 1, c + 0, -0.5 * T[2]);
      out.emplace_back(c + 1, c + 2, 0.5 * T[0]);
      out.emplace_back(c + 2, c + 0, 0.5 * T[1]);
      out.emplace_back(c + 2, c + 1, -0.5 * T[0]);
    }
  }
  for (const auto& s : springs_) {
    const Eigen::VectorXd d = s.d.B * gather(s.d.cols, q) + s.d.x0;
    const double l = d.norm();
    Eigen::MatrixXd Ke = Eigen::MatrixXd::Zero(dim_, dim_);
    if (l > 0.0) {
      const Eigen::VectorXd e = d / l, rate = s.d.B * gather(s.d.cols, v);
      const Eigen::MatrixXd P = Eigen::MatrixXd::Identity(dim_, dim_) - e * e.transpose();
      const double N = s.k * (l - s.rest) + s.c * e.dot(rate);
      Ke = e * (s.k * e + s.c * P * rate / l).transpose() + (N / l) * P;
    }
    scatter(s.d.cols, s.d.B.transpose() * Ke * s.d.B, out);
  }
  for (const auto& a : angles_) {
    const AngleState st = angle_state(a, q);
    const Eigen::VectorXd vl = gather(a.cols, v);
    const double moment = -a.k * st.delta - a.c * st.grad.dot(vl);
    scatter(a.cols,
            a.k * st.grad * st.grad.transpose() +
                a.c * st.grad * (st.hess.transpose() * vl).transpose() - moment * st.hess,
            out);
  }
}

void MultibodyForces::damping(const ConstRef& q, const ConstRef& /*v*/, Triplets& out) const {
  for (const auto& s : springs_) {
    const Eigen::VectorXd d = s.d.B * gather(s.d.cols, q) + s.d.x0;
    const double l = d.norm();
    const Eigen::VectorXd e = l > 0.0 ? Eigen::VectorXd(d / l) : Eigen::VectorXd::Zero(dim_);
    scatter(s.d.cols, s.d.B.transpose() * (s.c * e * e.transpose()) * s.d.B, out);
  }
  for (const auto& a : angles_) {
    const AngleState st = angle_state(a, q);
    scatter(a.cols, a.c * st.grad * st.grad.transpose(), out);
  }
}

MechanicalSystem::EnergyParts MultibodyForces::energy_parts(double t, double steps,
                                                            const ConstRef& q,
                                                            const ConstRef& v) const {
  MechanicalSystem::EnergyParts parts;
  add_load_energy(loads_, t, steps, q, v, parts.potential, parts.load_power);
  Eigen::VectorXd torque = Eigen::VectorXd::Zero(n_);
  for (const auto& tq : torques_) add_torque(tq, t, steps, q, torque);
  parts.load_power += torque.dot(v);
  for (const auto& s : springs_) {
    const Eigen::VectorXd d = s.d.B * gather(s.d.cols, q) + s.d.x0;
    const double l = d.norm();
    parts.potential += 0.5 * s.k * (l - s.rest) * (l - s.rest);
    if (l > 0.0) {
      const double rate = (d / l).dot(s.d.B * gather(s.d.cols, v));
      parts.dissipation_power += s.c * rate * rate;
    }
  }
  for (const auto& a : angles_) {
    const AngleState st = angle_state(a, q);
    const double rate = st.grad.dot(gather(a.cols, v));
    parts.potential += 0.5 * a.k * st.delta * st.delta;
    parts.dissipation_power += a.c * rate * rate;
  }
  return parts;
}

}  // namespace condyn
