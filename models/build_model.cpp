#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "models/model.hpp"
#include "models/scene_parser.hpp"

namespace condyn {

namespace {

// Relative size below which a (row-normalised) constraint set counts as rank deficient.
// Rows are scaled to unit norm first, so this compares directions: 1e-10 keeps constraints whose
// normals differ by more than ~1e-10 rad, far below anything a scene means on purpose.
constexpr double kRankTolerance = 1e-10;
// Initial conditions must satisfy the constraints to this relative accuracy: a scene writes them
// by hand in decimal, so a few hundred ulps of the terms' size is the right scale.
constexpr double kConsistencyTolerance = 1e-10;
// Refuse horizons that would write more rows than this (about 1 GB of CSV for a small model).
constexpr double kMaxOutputRows = 1e7;
// exp(709) is the largest finite double; leave headroom for amplitudes and derivatives.
constexpr double kMaxExponent = 700.0;

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

class Builder {
 public:
  explicit Builder(const SceneSpec& spec) : spec_(spec) {}

  [[noreturn]] void fail(const SourcePoint& where, const std::string& problem) const {
    throw SceneError(scene_message(spec_.file, where, problem));
  }

  int dof(const std::string& name, const SourcePoint& where) const {
    auto it = model_.dof_index.find(name);
    if (it == model_.dof_index.end()) {
      std::string hint;
      if (model_.dofs() <= 12) {
        for (const auto& d : model_.dof_names) hint += (hint.empty() ? "" : ", ") + d;
        hint = " (DOFs are: " + hint + ")";
      }
      fail(where, "no such DOF '" + name + "'" + hint);
    }
    return it->second;
  }

  void check_time_function(const TimeFunction& f, const SourcePoint& where) const {
    for (const auto& term : f.terms()) {
      if (term.kind == TimeTerm::Kind::exponential &&
          std::abs(term.rate) * spec_.solve.t_end > kMaxExponent && term.rate > 0) {
        fail(where,
             "exp(" + fmt(term.rate) + "*t) overflows before t_end = " + fmt(spec_.solve.t_end));
      }
    }
  }

  void set_dofs(std::vector<std::string> names) {
    model_.dof_names = std::move(names);
    for (int i = 0; i < model_.dofs(); ++i) model_.dof_index[model_.dof_names[i]] = i;
  }

  void build_truss2d() {
    const auto& m = spec_.model;
    std::vector<std::string> names;
    for (std::size_t k = 1; k <= m.nodes.size(); ++k) {
      names.push_back("ux" + std::to_string(k));
      names.push_back("uy" + std::to_string(k));
    }
    set_dofs(names);
    const int n = model_.dofs();
    double extent = 0.0;
    for (const auto& p : m.nodes) extent = std::max({extent, std::abs(p[0]), std::abs(p[1])});
    std::vector<Eigen::Triplet<double>> k_trip, m_trip;
    for (std::size_t e = 0; e < m.members.size(); ++e) {
      const auto& mem = m.members[e];
      const auto& pi = m.nodes[static_cast<std::size_t>(mem.node_i - 1)];
      const auto& pj = m.nodes[static_cast<std::size_t>(mem.node_j - 1)];
      const double dx = pj[0] - pi[0], dy = pj[1] - pi[1];
      const double length = std::hypot(dx, dy);
      if (length <= 1e-12 * std::max(extent, 1e-300)) {
        fail(mem.where, "member joins nodes " + std::to_string(mem.node_i) + " and " +
                            std::to_string(mem.node_j) + ", which coincide (zero length)");
      }
      // Small-displacement bar: k = EA/L along the unit axis (c, s).
      const double c = dx / length, s = dy / length, k = mem.EA / length;
      const std::array<int, 4> idx = {2 * (mem.node_i - 1), 2 * (mem.node_i - 1) + 1,
                                      2 * (mem.node_j - 1), 2 * (mem.node_j - 1) + 1};
      const std::array<double, 4> dir = {-c, -s, c, s};
      for (int a = 0; a < 4; ++a) {
        for (int b = 0; b < 4; ++b) k_trip.emplace_back(idx[a], idx[b], k * dir[a] * dir[b]);
      }
    }
    for (std::size_t k = 0; k < m.nodes.size(); ++k) {
      for (int d = 0; d < 2; ++d) {
        if (m.masses[k] != 0.0) {
          m_trip.emplace_back(static_cast<int>(2 * k) + d, static_cast<int>(2 * k) + d,
                              m.masses[k]);
        }
      }
    }
    model_.K.resize(n, n);
    model_.K.setFromTriplets(k_trip.begin(), k_trip.end());
    model_.M.resize(n, n);
    model_.M.setFromTriplets(m_trip.begin(), m_trip.end());
    model_.C.resize(n, n);
  }

  Eigen::SparseMatrix<double> sparse_psd(const std::vector<std::vector<double>>& rows,
                                         const std::string& key) const {
    const int n = static_cast<int>(rows.size());
    Eigen::MatrixXd dense(n, n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j)
        dense(i, j) = rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    }
    // Positive semi-definite up to roundoff of the largest eigenvalue.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, Eigen::EigenvaluesOnly);
    const double lo = eig.eigenvalues().minCoeff();
    const double hi = eig.eigenvalues().cwiseAbs().maxCoeff();
    if (lo < -1e-12 * std::max(hi, 1e-300)) {
      fail(SourcePoint{"model." + key, spec_.model.where.line},
           "is not positive semi-definite (smallest eigenvalue " + fmt(lo) + ")");
    }
    return dense.sparseView();
  }

  void build_matrix() {
    const auto& m = spec_.model;
    set_dofs(m.dofs);
    model_.M = sparse_psd(m.mass, "mass");
    model_.K = sparse_psd(m.stiffness, "stiffness");
    model_.C.resize(model_.dofs(), model_.dofs());
    if (!m.damping.empty()) model_.C = sparse_psd(m.damping, "damping");
    model_.M.makeCompressed();
    model_.K.makeCompressed();
    model_.C.makeCompressed();
  }

  void build_loads() {
    for (const auto& l : spec_.loads) {
      check_time_function(l.value, {l.where.path + ".value", l.where.line});
      model_.loads.push_back(Load{dof(l.dof, {l.where.path + ".dof", l.where.line}), l.value});
    }
  }

  void build_initial() {
    const int n = model_.dofs();
    model_.u0 = Eigen::VectorXd::Zero(n);
    model_.v0 = Eigen::VectorXd::Zero(n);
    for (const auto& [name, value] : spec_.initial.displacement) {
      model_.u0[dof(name, {"initial.displacement." + name, spec_.initial.where.line})] = value;
    }
    for (const auto& [name, value] : spec_.initial.velocity) {
      model_.v0[dof(name, {"initial.velocity." + name, spec_.initial.where.line})] = value;
    }
  }

  void build_constraints() {
    const int n = model_.dofs();
    std::vector<Eigen::Triplet<double>> trip;
    for (const auto& cs : spec_.constraints) {
      Constraint c;
      c.name = cs.name;
      c.level = cs.level;
      c.value = cs.value;
      c.where = cs.where;
      const SourcePoint value_at{cs.where.path + ".value", cs.where.line};
      for (const auto& [name, a] : cs.terms) {
        const int d = dof(name, {cs.where.path + ".terms." + name, cs.where.line});
        if (a != 0.0) c.coefficients.emplace_back(d, a);
      }
      std::sort(c.coefficients.begin(), c.coefficients.end());
      check_time_function(c.value, value_at);
      for (double b : c.value.breakpoints()) {
        fail(value_at,
             std::string("a step at t = ") + fmt(b) + " > 0 would make the prescribed " +
                 (c.level == ConstraintSpec::Level::position ? "displacement" : "velocity") +
                 " jump (an infinite " +
                 (c.level == ConstraintSpec::Level::position ? "velocity" : "acceleration") +
                 "); use a smooth function or a step at t = 0");
      }
      if (c.level == ConstraintSpec::Level::position) {
        c.position_value = c.value;
      } else {
        double a_u0 = 0.0;
        for (const auto& [d, a] : c.coefficients) a_u0 += a * model_.u0[d];
        std::vector<TimeTerm> terms = c.value.antiderivative().terms();
        terms.push_back(TimeFunction::constant(a_u0).terms().front());
        c.position_value = TimeFunction(std::move(terms));
      }
      const int row = static_cast<int>(model_.constraints.size());
      for (const auto& [d, a] : c.coefficients) trip.emplace_back(row, d, a);
      model_.constraints.push_back(std::move(c));
    }
    model_.A.resize(static_cast<int>(model_.constraints.size()), n);
    model_.A.setFromTriplets(trip.begin(), trip.end());
    model_.A.makeCompressed();
  }

  /// Rank of the row-normalised constraint matrix; a dependent set is named with the
  /// compatibility of its right-hand sides over the horizon.
  void check_rank() const {
    const int m = model_.constraint_count();
    if (m == 0) return;
    Eigen::MatrixXd at = Eigen::MatrixXd(model_.A).transpose();  // n x m, a column per constraint
    std::vector<double> row_norm;
    for (int j = 0; j < m; ++j) {
      const double norm = at.col(j).norm();
      row_norm.push_back(norm);
      if (norm == 0.0) {
        fail(model_.constraints[static_cast<std::size_t>(j)].where,
             "constraint '" + model_.constraints[static_cast<std::size_t>(j)].name +
                 "' has no nonzero coefficient");
      }
      at.col(j) /= norm;
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(at);
    qr.setThreshold(kRankTolerance);
    qr.compute(at);
    const int rank = static_cast<int>(qr.rank());
    if (rank == m) return;
    // The first `rank` pivot columns are independent; express the first dependent one in them.
    const auto& perm = qr.colsPermutation().indices();
    const int dep = perm[rank];
    Eigen::MatrixXd basis(at.rows(), rank);
    for (int k = 0; k < rank; ++k) basis.col(k) = at.col(perm[k]);
    const Eigen::VectorXd y = basis.colPivHouseholderQr().solve(at.col(dep));
    // Combination sum_k w_k c_k = 0 over the involved constraints (normalised rows).
    std::vector<std::pair<int, double>> combo = {{dep, 1.0}};
    for (int k = 0; k < rank; ++k) {
      if (std::abs(y[k]) > 1e-12) combo.emplace_back(perm[k], -y[k]);
    }
    std::string names;
    for (const auto& [j, w] : combo) {
      names += (names.empty() ? "'" : ", '") +
               model_.constraints[static_cast<std::size_t>(j)].name + "'";
    }
    // Compatible when the same combination of the right-hand sides vanishes over [0, t_end].
    double worst = 0.0, scale = 0.0;
    for (int s = 0; s <= 32; ++s) {
      const double t = spec_.solve.t_end * s / 32.0;
      double r = 0.0;
      for (const auto& [j, w] : combo) {
        const auto& c = model_.constraints[static_cast<std::size_t>(j)];
        const double gj = c.position_value.value(t) / row_norm[static_cast<std::size_t>(j)];
        r += w * gj;
        scale = std::max(scale, std::abs(w * gj));
      }
      worst = std::max(worst, std::abs(r));
    }
    const bool compatible = worst <= 1e-9 * std::max(scale, 1e-300) || worst == 0.0;
    fail(model_.constraints[static_cast<std::size_t>(dep)].where,
         "the constraints " + names + " are linearly dependent (constraint matrix rank " +
             std::to_string(rank) + " < " + std::to_string(m) + "); their right-hand sides are " +
             (compatible ? "compatible, so the set is redundant: remove one of them"
                         : "incompatible (residual " + fmt(worst) +
                               "), so the set is conflicting: no motion satisfies it"));
  }

  void check_degenerate_dofs() const {
    const int n = model_.dofs();
    std::vector<bool> has(static_cast<std::size_t>(n), false);
    for (const auto* mat : {&model_.M, &model_.K, &model_.C, &model_.A}) {
      for (int k = 0; k < mat->outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, k); it; ++it) {
          if (it.value() != 0.0) has[static_cast<std::size_t>(it.col())] = true;
        }
      }
    }
    for (int i = 0; i < n; ++i) {
      if (!has[static_cast<std::size_t>(i)]) {
        fail(spec_.model.where, "DOF '" + model_.dof_names[static_cast<std::size_t>(i)] +
                                    "' has neither mass nor stiffness nor damping nor a "
                                    "constraint: its motion is undefined");
      }
    }
  }

  void check_initial_consistency() const {
    for (const auto& c : model_.constraints) {
      double au = 0.0, av = 0.0, su = 0.0, sv = 0.0;
      for (const auto& [d, a] : c.coefficients) {
        au += a * model_.u0[d];
        av += a * model_.v0[d];
        su += std::abs(a * model_.u0[d]);
        sv += std::abs(a * model_.v0[d]);
      }
      const bool position = c.level == ConstraintSpec::Level::position;
      const std::string where = "constraint '" + c.name + "'";
      if (position) {
        const double g = c.value.value(0.0);
        if (std::abs(au - g) > kConsistencyTolerance * std::max({su, std::abs(g), 1e-300})) {
          fail(spec_.initial.where.line ? spec_.initial.where : c.where,
               "initial displacements violate " + where + ": a·u(0) = " + fmt(au) +
                   " but the constraint requires " + fmt(g) + " (residual " + fmt(au - g) + ")");
        }
      }
      const double gv = position ? c.value.derivative(1, 0.0) : c.value.value(0.0);
      if (std::abs(av - gv) > kConsistencyTolerance * std::max({sv, std::abs(gv), 1e-300})) {
        fail(spec_.initial.where.line ? spec_.initial.where : c.where,
             "initial velocities violate " + where + ": a·v(0) = " + fmt(av) +
                 " but the constraint requires " + fmt(gv) + " (residual " + fmt(av - gv) +
                 "); set [initial] velocity to match");
      }
    }
  }

  void check_output() const {
    const double rows = spec_.solve.t_end / spec_.solve.output_step + 1.0;
    if (rows > kMaxOutputRows) {
      fail({"solve.output_step", spec_.solve.where.line},
           "would write " + fmt(rows) + " rows (limit " + fmt(kMaxOutputRows) +
               "): increase output_step");
    }
    for (const auto& s : spec_.solve.slaves) (void)dof(s, {"solve.slaves", spec_.solve.where.line});
  }

  Model build() {
    model_.file = spec_.file;
    model_.name = spec_.name;
    model_.solve = spec_.solve;
    model_.output = spec_.output;
    if (spec_.model.type == ModelSpec::Type::truss2d) {
      build_truss2d();
    } else {
      build_matrix();
    }
    build_loads();
    build_initial();
    build_constraints();
    check_degenerate_dofs();
    check_rank();
    check_initial_consistency();
    check_output();
    return std::move(model_);
  }

 private:
  const SceneSpec& spec_;
  Model model_;
};

}  // namespace

Model build_model(const SceneSpec& spec) { return Builder(spec).build(); }

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

std::pair<double, double> Model::drift(double t, const Eigen::VectorXd& u,
                                       const Eigen::VectorXd& v) const {
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
