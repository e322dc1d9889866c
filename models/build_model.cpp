#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "models/initial_projection.hpp"
#include "models/linear_rows.hpp"
#include "models/linear_system.hpp"
#include "models/model.hpp"
#include "models/point_mass_system.hpp"
#include "models/scene_parser.hpp"
#include "models/sleigh.hpp"
#include "models/zero_sum.hpp"

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
// The rank check and [initial] project factor dense matrices (constraints x DOFs): refuse sizes
// whose memory and time would look like a hang (4e6 doubles = 32 MB; a QR of about 10 s).
constexpr double kMaxDenseEntries = 4e6;
// The solvers, `info` and the exact and elimination paths use dense DOF x DOF and constraint x DOF
// matrices: 5000 of either is about 40 s and 600 MB for `run`; 10x more would take hours and GBs.
constexpr int kMaxDofs = 5000;
constexpr int kMaxConstraints = 5000;

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

/// An upper bound of |d^order/dt^order term(t)| over [0, t_end], order in {0, 1, 2}; infinite when
/// the term leaves the double range there.
double magnitude_bound(const TimeTerm& term, int order, double t_end) {
  if (term.is_zero()) return 0.0;
  switch (term.kind) {
    case TimeTerm::Kind::step:
      return order == 0 ? std::abs(term.amplitude) : 0.0;
    case TimeTerm::Kind::polynomial: {
      double sum = 0.0;
      for (std::size_t k = static_cast<std::size_t>(order); k < term.coefficients.size(); ++k) {
        if (term.coefficients[k] == 0.0) continue;
        double factor = std::abs(term.coefficients[k]);
        for (int j = 0; j < order; ++j)
          factor *= static_cast<double>(k - static_cast<std::size_t>(j));
        sum += factor * std::pow(t_end, static_cast<double>(k - static_cast<std::size_t>(order)));
      }
      return sum;
    }
    case TimeTerm::Kind::harmonic:
      return std::abs(term.amplitude) * std::pow(std::abs(term.omega), order);
    case TimeTerm::Kind::exponential:
      return std::abs(term.amplitude) * std::pow(std::abs(term.rate), order) *
             std::exp(std::max(term.rate * t_end, 0.0));
  }
  return 0.0;
}

/// The largest of the bounds of f, f' and f'' over [0, t_end] (infinite on overflow).
double magnitude_bound(const TimeFunction& f, double t_end) {
  double worst = 0.0;
  for (int order = 0; order <= 2; ++order) {
    double sum = 0.0;
    for (const auto& term : f.terms()) sum += magnitude_bound(term, order, t_end);
    worst = std::max(worst, sum);
  }
  return worst;
}

bool all_finite(const Eigen::SparseMatrix<double>& m) {
  for (Eigen::Index k = 0; k < m.nonZeros(); ++k) {
    if (!std::isfinite(m.valuePtr()[k])) return false;
  }
  return true;
}

class Builder {
 public:
  Builder(const SceneSpec& spec, BuildReport& report) : spec_(spec), report_(report) {}

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

  /// f, f' and f'' must stay finite over [0, t_end]: an overflowing load or right-hand side would
  /// reach the solver as inf or NaN.
  void check_time_function(const TimeFunction& f, const SourcePoint& where) const {
    for (const auto& term : f.terms()) {
      if (term.kind == TimeTerm::Kind::exponential &&
          std::abs(term.rate) * spec_.solve.t_end > kMaxExponent && term.rate > 0) {
        fail(where,
             "exp(" + fmt(term.rate) + "*t) overflows before t_end = " + fmt(spec_.solve.t_end));
      }
    }
    if (!std::isfinite(magnitude_bound(f, spec_.solve.t_end))) {
      fail(where, f.describe() +
                      " or its first two time derivatives overflow the double range "
                      "(about 1.8e308) before t_end = " +
                      fmt(spec_.solve.t_end));
    }
  }

  void set_dofs(std::vector<std::string> names) {
    model_.dof_names = std::move(names);
    for (int i = 0; i < model_.dofs(); ++i) model_.dof_index[model_.dof_names[i]] = i;
  }

  void build_truss() {
    const auto& m = spec_.model;
    const int dim = m.dimension;
    static constexpr std::array<const char*, 3> kAxes = {"ux", "uy", "uz"};
    std::vector<std::string> names;
    for (std::size_t k = 1; k <= m.nodes.size(); ++k) {
      for (int d = 0; d < dim; ++d)
        names.push_back(kAxes[static_cast<std::size_t>(d)] + std::to_string(k));
    }
    set_dofs(names);
    const int n = model_.dofs();
    double extent = 0.0;
    for (const auto& p : m.nodes) {
      for (double x : p) extent = std::max(extent, std::abs(x));
    }
    nonlinear_truss_ = m.geometry == ModelSpec::Geometry::nonlinear;
    for (std::size_t e = 0; e < m.members.size(); ++e) {
      const auto& mem = m.members[e];
      const auto& pi = m.nodes[static_cast<std::size_t>(mem.node_i - 1)];
      const auto& pj = m.nodes[static_cast<std::size_t>(mem.node_j - 1)];
      // hypot: no overflow or underflow of the squares for coordinates near the double range.
      const double length = std::hypot(pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]);
      if (!std::isfinite(length)) {
        fail(mem.where, "member joins nodes " + std::to_string(mem.node_i) + " and " +
                            std::to_string(mem.node_j) +
                            ", whose distance overflows the double range (coordinates too large)");
      }
      if (length <= 1e-12 * std::max(extent, 1e-300)) {
        fail(mem.where, "member joins nodes " + std::to_string(mem.node_i) + " and " +
                            std::to_string(mem.node_j) + ", which coincide (zero length)");
      }
      if (!mem.rigid && !std::isfinite(mem.EA / length)) {
        fail({mem.where.path + ".EA", mem.where.line},
             "EA / length = " + fmt(mem.EA) + " / " + fmt(length) +
                 " overflows the double range: the stiffness would be infinite");
      }
      const PointMassLayout::Bar bar{mem.node_i - 1, mem.node_j - 1, mem.EA, length};
      if (mem.rigid) {
        layout_.rods.push_back(bar);
        rod_where_.push_back(mem.where);
        nonlinear_truss_ = true;
      } else {
        layout_.bars.push_back(bar);
      }
    }
    layout_.dimension = dim;
    layout_.nodes = m.nodes;
    layout_.masses = m.masses;
    layout_.nonlinear_geometry = m.geometry == ModelSpec::Geometry::nonlinear;
    // Small-displacement stiffness: k = EA/L along the unit axis (the linear model's K, and the
    // system's own K for linear geometry).
    std::vector<Eigen::Triplet<double>> k_trip, m_trip;
    for (const auto& b : layout_.bars) {
      const auto& pi = m.nodes[static_cast<std::size_t>(b.i)];
      const auto& pj = m.nodes[static_cast<std::size_t>(b.j)];
      std::vector<int> idx;
      std::vector<double> dir;
      for (int sign : {-1, 1}) {
        for (int d = 0; d < dim; ++d) {
          idx.push_back((sign < 0 ? b.i : b.j) * dim + d);
          dir.push_back(sign * (pj[static_cast<std::size_t>(d)] - pi[static_cast<std::size_t>(d)]) /
                        b.length);
        }
      }
      for (std::size_t a = 0; a < idx.size(); ++a) {
        for (std::size_t c = 0; c < idx.size(); ++c) {
          k_trip.emplace_back(idx[a], idx[c], b.EA / b.length * dir[a] * dir[c]);
        }
      }
    }
    for (std::size_t k = 0; k < m.nodes.size(); ++k) {
      for (int d = 0; d < dim; ++d) {
        if (m.masses[k] != 0.0) {
          m_trip.emplace_back(static_cast<int>(k) * dim + d, static_cast<int>(k) * dim + d,
                              m.masses[k]);
        }
      }
    }
    model_.K.resize(n, n);
    model_.K.setFromTriplets(k_trip.begin(), k_trip.end());
    model_.M.resize(n, n);
    model_.M.setFromTriplets(m_trip.begin(), m_trip.end());
    model_.C.resize(n, n);
    // Gravity: a constant load m g on every node with mass, before the scene's loads.
    for (std::size_t k = 0; k < m.nodes.size() && !m.gravity.empty(); ++k) {
      for (int d = 0; d < dim; ++d) {
        const double w = m.masses[k] * m.gravity[static_cast<std::size_t>(d)];
        if (!std::isfinite(w)) {
          fail({"model.gravity", m.where.line}, "the weight of node " + std::to_string(k + 1) +
                                                    " (mass " + fmt(m.masses[k]) + " times " +
                                                    fmt(m.gravity[static_cast<std::size_t>(d)]) +
                                                    ") overflows the double range");
        }
        if (w != 0.0) {
          model_.loads.push_back(Load{static_cast<int>(k) * dim + d, TimeFunction::constant(w)});
        }
      }
    }
  }

  /// The built-in benchmark models: every parameter fixed by the published problem.
  void build_benchmark() {
    const auto type = spec_.model.type;
    const std::string name = type == ModelSpec::Type::andrews    ? "andrews"
                             : type == ModelSpec::Type::car_axis ? "car_axis"
                                                                 : "pendulum";
    if (!spec_.loads.empty()) {
      fail(spec_.loads.front().where,
           "the built-in model '" + name + "' fixes its own forces: remove the [[load]] entries");
    }
    if (!spec_.constraints.empty()) {
      fail(spec_.constraints.front().where, "the built-in model '" + name +
                                                "' fixes its own constraints: remove the "
                                                "[[constraint]] entries");
    }
    const BenchmarkModel b = type == ModelSpec::Type::andrews    ? make_andrews()
                             : type == ModelSpec::Type::car_axis ? make_car_axis()
                                                                 : make_pendulum();
    set_dofs(b.dof_names);
    model_.system = b.system;
    model_.nonlinear = true;
    model_.reference = b.reference;
    model_.description = b.description;
    base_u0_ = b.u0;
    base_v0_ = b.v0;
    for (const auto& c : b.constraint_names) {
      Constraint row;
      row.name = c;
      row.nonlinear_kind = "nonlinear holonomic (" + name + ")";
      row.where = spec_.model.where;
      model_.constraints.push_back(row);
    }
  }

  void build_sleigh() {
    set_dofs({"x", "y", "theta"});
    if (!spec_.constraints.empty()) {
      fail(spec_.constraints.front().where,
           "the sleigh brings its own knife-edge constraint: remove the [[constraint]] entries");
    }
    model_.description =
        "Chaplygin sleigh: a rigid body on a knife edge at distance contact_offset ahead of its "
        "centre of mass";
  }

  void finish_sleigh() {
    const auto& m = spec_.model;
    model_.nonlinear = true;
    model_.system = make_sleigh({m.body_mass, m.inertia, m.contact_offset, model_.loads});
    Constraint row;
    row.name = "knife_edge";
    row.level = ConstraintSpec::Level::velocity;
    row.nonlinear_kind =
        "no sideways slip at the contact point: -sin(theta) x' + cos(theta) y' + a theta' = 0";
    row.nonholonomic = true;
    row.where = spec_.model.where;
    model_.constraints.push_back(row);
  }

  /// Truss with rigid members or large-displacement bars: the point-mass system, its rod rows
  /// after the linear ones.
  void finish_point_masses() {
    layout_.loads = model_.loads;
    layout_.linear_rows = model_.constraints;
    model_.nonlinear = true;
    model_.system = std::make_shared<PointMassSystem>(layout_);
    for (std::size_t r = 0; r < layout_.rods.size(); ++r) {
      const auto& b = layout_.rods[r];
      Constraint row;
      row.name = "rigid_" + std::to_string(b.i + 1) + "_" + std::to_string(b.j + 1);
      row.nonlinear_kind = "distance |x" + std::to_string(b.j + 1) + " - x" +
                           std::to_string(b.i + 1) + "| = " + fmt(b.length);
      row.where = rod_where_[r];
      model_.constraints.push_back(row);
    }
  }

  /// An evaluator of the model as built so far: its nonlinear system, or the linear system of its
  /// matrices and rows (the Model's own LinearSystem is made last, from the final model).
  [[nodiscard]] std::unique_ptr<MechanicalSystem> evaluator() const {
    if (model_.nonlinear) return model_.evaluator();
    return std::make_unique<LinearSystem>(model_);
  }

  /// M, C, K, A of a nonlinear model: its linearization at t = 0, (u0, v0).
  void linearize() {
    const auto evaluator = model_.evaluator();
    MechanicalSystem& s = *evaluator;
    model_.M = s.mass(0.0, model_.u0);
    model_.K = -s.force_jacobian_u(0.0, model_.u0, model_.v0);
    model_.C = -s.force_jacobian_v(0.0, model_.u0, model_.v0);
    if (model_.C.rows() != model_.dofs()) model_.C.resize(model_.dofs(), model_.dofs());
    model_.A = s.constraint_jacobian(0.0, model_.u0);
    for (auto* mat : {&model_.M, &model_.K, &model_.C, &model_.A}) mat->prune(0.0);
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
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      fail(SourcePoint{"model." + key, spec_.model.where.line},
           "has eigenvalues beyond the double range: the entries are too large");
    }
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
    // Gravity loads come first; several loads on one DOF add up, and so must stay finite.
    std::vector<double> total(static_cast<std::size_t>(model_.dofs()), 0.0);
    for (const auto& l : model_.loads) {
      total[static_cast<std::size_t>(l.dof)] += magnitude_bound(l.value, spec_.solve.t_end);
    }
    for (const auto& l : spec_.loads) {
      const SourcePoint value_at{l.where.path + ".value", l.where.line};
      check_time_function(l.value, value_at);
      const int d = dof(l.dof, {l.where.path + ".dof", l.where.line});
      auto& sum = total[static_cast<std::size_t>(d)];
      sum += magnitude_bound(l.value, spec_.solve.t_end);
      if (!std::isfinite(sum)) {
        fail(value_at, "the loads on DOF '" + l.dof +
                           "' add up to more than the double range (about 1.8e308)");
      }
      model_.loads.push_back(Load{d, l.value});
    }
  }

  void build_initial() {
    const int n = model_.dofs();
    model_.u0 = base_u0_.size() == n ? base_u0_ : Eigen::VectorXd::Zero(n);
    model_.v0 = base_v0_.size() == n ? base_v0_ : Eigen::VectorXd::Zero(n);
    for (const auto& [name, value] : spec_.initial.displacement) {
      model_.u0[dof(name, {"initial.displacement." + name, spec_.initial.where.line})] = value;
    }
    for (const auto& [name, value] : spec_.initial.velocity) {
      model_.v0[dof(name, {"initial.velocity." + name, spec_.initial.where.line})] = value;
    }
  }

  /// A coefficient must carry information: a subnormal one has lost its precision (and its
  /// square underflows to 0 in any row norm), and one below eps times the row's largest vanishes
  /// in every sum a·u, so it only pretends that its DOF is constrained.
  void check_coefficients(const ConstraintSpec& cs) const {
    double largest = 0.0;
    for (const auto& [name, a] : cs.terms) largest = std::max(largest, std::abs(a));
    for (const auto& [name, a] : cs.terms) {
      const SourcePoint key{cs.where.path + ".terms." + name, cs.where.line};
      if (a != 0.0 && std::abs(a) < std::numeric_limits<double>::min()) {
        fail(key, "the coefficient " + fmt(a) +
                      " is subnormal (below 2.2e-308): it has lost its precision; rescale the "
                      "constraint or remove the term");
      }
      if (a != 0.0 && std::abs(a) < std::numeric_limits<double>::epsilon() * largest) {
        fail(key, "the coefficient " + fmt(a) + " is below the roundoff of the row's largest (" +
                      fmt(largest) +
                      "): it changes no sum a·u, so the term only seems to constrain '" + name +
                      "'; remove it or rescale");
      }
    }
  }

  void build_constraints() {
    const int n = model_.dofs();
    std::vector<Eigen::Triplet<double>> trip;
    for (int node : spec_.model.supports) {  // a fixed support: every DOF of the node is zero
      for (int d = 0; d < spec_.model.dimension; ++d) {
        Constraint c;
        const int dof = (node - 1) * spec_.model.dimension + d;
        c.name = "fix_" + model_.dof_names[static_cast<std::size_t>(dof)];
        c.coefficients = {{dof, 1.0}};
        c.position_value = c.value;
        c.where = {"model.supports", spec_.model.where.line};
        const int row = static_cast<int>(model_.constraints.size());
        trip.emplace_back(row, c.coefficients.front().first, 1.0);
        model_.constraints.push_back(std::move(c));
      }
    }
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
      check_coefficients(cs);
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
        double a_u0 = 0.0, size = 0.0;
        for (const auto& [d, a] : c.coefficients) {
          a_u0 += a * model_.u0[d];
          size += std::abs(a * model_.u0[d]);
        }
        if (!std::isfinite(size)) {
          fail(spec_.initial.where.line ? spec_.initial.where : cs.where,
               "a·u(0) of constraint '" + c.name +
                   "' overflows the double range (coefficients times initial displacements)");
        }
        std::vector<TimeTerm> terms = c.value.antiderivative().terms();
        terms.push_back(TimeFunction::constant(a_u0).terms().front());
        c.position_value = TimeFunction(std::move(terms));
        // h(t) = A sin(omega t) integrates to A/omega (1 - cos(omega t)): a tiny omega or rate
        // overflows there even when h itself is small.
        if (!std::isfinite(magnitude_bound(c.position_value, spec_.solve.t_end))) {
          fail(value_at,
               "integrating this velocity constraint's right-hand side from t = 0 gives " +
                   c.position_value.describe() +
                   ", which overflows the double range before t_end = " + fmt(spec_.solve.t_end) +
                   " (is an omega or rate almost 0?)");
        }
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
  /// compatibility of its right-hand sides over the horizon. Constraints that share no DOF, even
  /// through others, are independent of each other: each connected group is factored on its own
  /// (supports and other single-DOF rows cost nothing), and a group too large for a dense QR is
  /// refused rather than left to run out of memory or time.
  /// A redundant constraint (a combination of others, right-hand sides compatible) that the scene
  /// asks to drop.
  struct Dependent {
    int row = 0;
    std::string others;  ///< the constraints it combines, quoted
  };

  /// Removes constraint `d.row` from the linear model and reports it.
  void drop_constraint(const Dependent& d) {
    const auto row = static_cast<std::size_t>(d.row);
    report_.dropped_constraints.push_back("'" + model_.constraints[row].name +
                                          "' (a combination of " + d.others + ")");
    model_.constraints.erase(model_.constraints.begin() + d.row);
    std::vector<Eigen::Triplet<double>> kept;
    for (int k = 0; k < model_.A.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(model_.A, k); it; ++it) {
        if (it.row() == d.row) continue;
        kept.emplace_back(it.row() > d.row ? it.row() - 1 : it.row(), it.col(), it.value());
      }
    }
    model_.A.resize(model_.A.rows() - 1, model_.A.cols());
    model_.A.setFromTriplets(kept.begin(), kept.end());
  }

  /// Refuses dependent constraints, naming them, unless they are redundant and the scene asks to
  /// drop them ([solve] redundant = "drop", linear models): then returns the one to drop.
  [[nodiscard]] std::optional<Dependent> check_rank() const {
    const int m = model_.constraint_count();
    if (m == 0) return std::nullopt;
    const auto& constraints = model_.constraints;
    const Eigen::SparseMatrix<double, Eigen::RowMajor> a(model_.A);
    std::vector<double> row_norm;
    std::vector<int> parent(static_cast<std::size_t>(m));
    std::vector<int> owner(static_cast<std::size_t>(model_.dofs()), -1);  // first row on a DOF
    const auto root = [&parent](int j) {
      while (parent[static_cast<std::size_t>(j)] != j) {
        j = parent[static_cast<std::size_t>(j)] =
            parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(j)])];
      }
      return j;
    };
    for (int j = 0; j < m; ++j) {
      parent[static_cast<std::size_t>(j)] = j;
      Eigen::VectorXd values(a.row(j).nonZeros());
      Eigen::Index k = 0;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, j); it; ++it) {
        values[k++] = it.value();
        int& first = owner[static_cast<std::size_t>(it.col())];
        if (first < 0) {
          first = j;
        } else {  // join the groups; the root stays the group's first row
          const int r1 = root(first), r2 = root(j);
          parent[static_cast<std::size_t>(std::max(r1, r2))] = std::min(r1, r2);
        }
      }
      // stableNorm: coefficients near the double range neither overflow nor underflow.
      const double norm = values.size() ? values.stableNorm() : 0.0;
      row_norm.push_back(norm);
      if (norm == 0.0) {
        fail(constraints[static_cast<std::size_t>(j)].where,
             "constraint '" + constraints[static_cast<std::size_t>(j)].name +
                 "' has no nonzero coefficient");
      }
    }
    std::vector<std::vector<int>> groups(static_cast<std::size_t>(m));
    for (int j = 0; j < m; ++j) groups[static_cast<std::size_t>(root(j))].push_back(j);
    int rank = 0;
    int dep = -1;  // the first dependent constraint, and the combination that shows it
    std::vector<std::pair<int, double>> combo;
    std::vector<int> local(static_cast<std::size_t>(model_.dofs()), -1);
    for (const auto& rows : groups) {
      if (rows.empty()) continue;
      std::vector<int> dofs;
      for (int j : rows) {
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, j); it; ++it) {
          if (local[static_cast<std::size_t>(it.col())] < 0) {
            local[static_cast<std::size_t>(it.col())] = 0;
            dofs.push_back(static_cast<int>(it.col()));
          }
        }
      }
      std::sort(dofs.begin(), dofs.end());
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        local[static_cast<std::size_t>(dofs[i])] = static_cast<int>(i);
      }
      const auto mc = static_cast<Eigen::Index>(rows.size());
      const auto nc = static_cast<Eigen::Index>(dofs.size());
      if (static_cast<double>(mc) * static_cast<double>(nc) > kMaxDenseEntries) {
        fail(constraints[static_cast<std::size_t>(rows.front())].where,
             "constraint '" + constraints[static_cast<std::size_t>(rows.front())].name +
                 "' is coupled through shared DOFs to " + std::to_string(mc - 1) + " others over " +
                 std::to_string(nc) + " DOFs: too many for the dense rank check (limit " +
                 fmt(kMaxDenseEntries) +
                 " constraint-DOF pairs); condyn treats small and medium models");
      }
      // n_c x m_c, a column per constraint, normalised.
      Eigen::MatrixXd at = Eigen::MatrixXd::Zero(nc, mc);
      for (Eigen::Index c = 0; c < mc; ++c) {
        const int j = rows[static_cast<std::size_t>(c)];
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, j); it; ++it) {
          at(local[static_cast<std::size_t>(it.col())], c) =
              it.value() / row_norm[static_cast<std::size_t>(j)];
        }
      }
      for (int d : dofs) local[static_cast<std::size_t>(d)] = -1;
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(at.rows(), at.cols());
      qr.setThreshold(kRankTolerance);
      qr.compute(at);
      const int group_rank = static_cast<int>(qr.rank());
      rank += group_rank;
      if (group_rank == mc || dep >= 0) continue;
      // The first `group_rank` pivot columns are independent; express the first dependent one in
      // them.
      const auto& perm = qr.colsPermutation().indices();
      dep = rows[static_cast<std::size_t>(perm[group_rank])];
      Eigen::MatrixXd basis(at.rows(), group_rank);
      for (int k = 0; k < group_rank; ++k) basis.col(k) = at.col(perm[k]);
      const Eigen::VectorXd y = basis.colPivHouseholderQr().solve(at.col(perm[group_rank]));
      // Combination sum_k w_k c_k = 0 over the involved constraints (normalised rows).
      combo = {{dep, 1.0}};
      for (int k = 0; k < group_rank; ++k) {
        if (std::abs(y[k]) > 1e-12)
          combo.emplace_back(rows[static_cast<std::size_t>(perm[k])], -y[k]);
      }
    }
    if (dep < 0) return std::nullopt;
    std::string names;
    for (const auto& [j, w] : combo) {
      names += (names.empty() ? "'" : ", '") + constraints[static_cast<std::size_t>(j)].name + "'";
    }
    // Compatible when the same combination of the right-hand sides vanishes identically over
    // [0, t_end]: decided from the terms (zero_sum.hpp), never from samples, which two
    // different functions can share (0 and 1 - cos(64 pi t) agree at every multiple of 1/32).
    std::vector<std::pair<double, const TimeFunction*>> sum;
    for (const auto& [j, w] : combo) {
      const auto& c = constraints[static_cast<std::size_t>(j)];
      sum.emplace_back(w / row_norm[static_cast<std::size_t>(j)], &c.position_value);
    }
    const ZeroSumVerdict verdict = weighted_sum_vanishes(sum, spec_.solve.t_end);
    if (verdict.kind == ZeroSumVerdict::Kind::undecided) {
      fail(constraints[static_cast<std::size_t>(dep)].where,
           "the constraints " + names + " are linearly dependent (constraint matrix rank " +
               std::to_string(rank) + " < " + std::to_string(m) +
               "), and condyn cannot decide whether their right-hand sides are compatible: " +
               verdict.detail +
               "; write the same numbers where the functions are meant to be equal, or remove "
               "one of the constraints");
    }
    const bool compatible = verdict.kind == ZeroSumVerdict::Kind::zero;
    if (compatible && spec_.solve.drop_redundant && !model_.is_nonlinear()) {
      std::string others;
      for (const auto& [j, w] : combo) {
        if (j == dep) continue;
        others +=
            (others.empty() ? "'" : ", '") + constraints[static_cast<std::size_t>(j)].name + "'";
      }
      return Dependent{dep, others};
    }
    fail(constraints[static_cast<std::size_t>(dep)].where,
         "the constraints " + names + " are linearly dependent (constraint matrix rank " +
             std::to_string(rank) + " < " + std::to_string(m) + "); their right-hand sides are " +
             (compatible
                  ? std::string("compatible, so the set is redundant: remove one of them") +
                        (model_.is_nonlinear() ? ""
                                               : ", or set [solve] redundant = \"drop\" to drop it")
                  : "incompatible (the combination that vanishes on the left leaves " +
                        verdict.detail +
                        " on the right), so the set is conflicting: no motion "
                        "satisfies it"));
  }

  /// The last line of defence against a silent inf or NaN: whatever the checks above let through,
  /// the matrices and the initial state handed to the solvers are finite.
  /// Warns (does not refuse) about magnitudes that double precision cannot carry well: M, C, K or
  /// A whose largest entry lies beyond 1e±15 (a unit mistake, most likely), and diagonals of M or
  /// K whose largest and smallest positive entries differ by more than 1/eps ≈ 4.5e15 (the soft
  /// or light DOFs are then lost in the roundoff of the stiff or heavy ones).
  void check_magnitudes() {
    constexpr double kFar = 1e15, kSpread = 4.5e15;
    const std::pair<const Eigen::SparseMatrix<double>*, const char*> matrices[] = {
        {&model_.M, "mass matrix M"},
        {&model_.C, "damping matrix C"},
        {&model_.K, "stiffness matrix K"},
        {&model_.A, "constraint matrix A"}};
    for (const auto& [mat, name] : matrices) {
      double hi = 0.0;
      double dlo = std::numeric_limits<double>::infinity(), dhi = 0.0;
      for (int k = 0; k < mat->outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, k); it; ++it) {
          const double a = std::abs(it.value());
          if (a == 0.0) continue;
          hi = std::max(hi, a);
          if (it.row() == it.col() && it.value() > 0.0) {
            dlo = std::min(dlo, it.value());
            dhi = std::max(dhi, it.value());
          }
        }
      }
      // The largest entry sets the matrix's scale; single tiny entries are roundoff (cos 90°).
      if (hi > kFar || (hi > 0.0 && hi < 1.0 / kFar)) {
        report_.warnings.push_back(std::string("the ") + name + " has entries up to magnitude " +
                                   fmt(hi) + ": beyond 1e-15 ... 1e15, check the units");
      }
      const bool diagonal_matters = mat == &model_.M || mat == &model_.K;
      if (diagonal_matters && dhi > 0.0 && dhi / dlo > kSpread) {
        report_.warnings.push_back(std::string("the diagonal of the ") + name + " spans " +
                                   fmt(dlo) + " to " + fmt(dhi) + " (ratio " + fmt(dhi / dlo) +
                                   "): beyond 1/eps of double precision (4.5e15), the smallest "
                                   "entries are lost in roundoff");
      }
    }
  }

  void check_finite() const {
    const std::pair<const Eigen::SparseMatrix<double>*, const char*> matrices[] = {
        {&model_.M, "mass matrix M"},
        {&model_.C, "damping matrix C"},
        {&model_.K, "stiffness matrix K"},
        {&model_.A, "constraint matrix A"}};
    // A nonlinear model's matrices are its linearization at (u0, v0): too large an initial state
    // is the likelier cause there.
    const bool at_start = model_.is_nonlinear() && spec_.initial.where.line > 0;
    for (const auto& [mat, name] : matrices) {
      if (!all_finite(*mat)) {
        fail(at_start ? spec_.initial.where : spec_.model.where,
             std::string("the ") + name +
                 (at_start ? " linearized at the initial state has entries beyond the double "
                             "range: are the initial values too large?"
                           : " has entries beyond the double range: the scene's numbers are too "
                             "large"));
      }
    }
    if (!model_.u0.allFinite() || !model_.v0.allFinite()) {
      fail(spec_.initial.where.line ? spec_.initial.where : spec_.model.where,
           "the initial state is not finite (it overflows the double range)");
    }
  }

  /// Sizes the dense parts of condyn can treat (README "Known limitations": small and medium
  /// models), refused before any dense work rather than left to exhaust memory or time.
  void check_size() const {
    if (model_.dofs() > kMaxDofs) {
      fail(spec_.model.where, std::to_string(model_.dofs()) +
                                  " DOFs: more than condyn's limit of " + std::to_string(kMaxDofs) +
                                  " (its solvers factor dense DOF x DOF matrices)");
    }
    if (model_.constraint_count() > kMaxConstraints) {
      const auto& last = model_.constraints.back();
      fail(last.where, std::to_string(model_.constraint_count()) +
                           " constraints: more than condyn's limit of " +
                           std::to_string(kMaxConstraints) +
                           " (its solvers factor dense constraint x constraint matrices)");
    }
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
    if (model_.is_nonlinear()) {
      check_nonlinear_consistency();
      return;
    }
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
      if (!std::isfinite(su) || !std::isfinite(sv)) {
        fail(spec_.initial.where.line ? spec_.initial.where : c.where,
             "a·u(0) or a·v(0) of " + where +
                 " overflows the double range (coefficients times initial values)");
      }
      // Negated comparisons: a NaN residual is a violation, never a pass.
      if (position) {
        const double g = c.value.value(0.0);
        if (!(std::abs(au - g) <= kConsistencyTolerance * std::max({su, std::abs(g), 1e-300}))) {
          fail(spec_.initial.where.line ? spec_.initial.where : c.where,
               "initial displacements violate " + where + ": a·u(0) = " + fmt(au) +
                   " but the constraint requires " + fmt(g) + " (residual " + fmt(au - g) + ")");
        }
      }
      const double gv = position ? c.value.derivative(1, 0.0) : c.value.value(0.0);
      if (!(std::abs(av - gv) <= kConsistencyTolerance * std::max({sv, std::abs(gv), 1e-300}))) {
        fail(spec_.initial.where.line ? spec_.initial.where : c.where,
             "initial velocities violate " + where + ": a·v(0) = " + fmt(av) +
                 " but the constraint requires " + fmt(gv) + " (residual " + fmt(av - gv) +
                 "); set [initial] velocity to match");
      }
    }
  }

  /// φ(0, u0) and ψ(0, u0, v0) of a nonlinear model, relative to the size of the state.
  void check_nonlinear_consistency() const {
    const auto evaluator = model_.evaluator();
    MechanicalSystem& s = *evaluator;
    const int m = model_.constraint_count();
    Eigen::VectorXd phi(m), psi(m);
    s.position_residual(0.0, model_.u0, phi);
    s.velocity_residual(0.0, model_.u0, model_.v0, psi);
    const double u_scale = std::max(1.0, model_.u0.lpNorm<Eigen::Infinity>());
    const double v_scale = std::max(1.0, model_.v0.lpNorm<Eigen::Infinity>());
    for (int i = 0; i < m; ++i) {
      const auto& c = model_.constraints[static_cast<std::size_t>(i)];
      // Negated comparisons: a NaN residual is a violation, never a pass.
      const bool bad_u = !(std::abs(phi[i]) <= kConsistencyTolerance * u_scale);
      const bool bad_v = !(std::abs(psi[i]) <= kConsistencyTolerance * v_scale * u_scale);
      if (!bad_u && !bad_v) continue;
      fail(spec_.initial.where.line ? spec_.initial.where : c.where,
           std::string("initial ") + (bad_u ? "displacements" : "velocities") +
               " violate constraint '" + c.name + "'" +
               (c.nonlinear_kind.empty() ? "" : " (" + c.nonlinear_kind + ")") + ": residual " +
               fmt(bad_u ? phi[i] : psi[i]) +
               "; fix [initial], or set [initial] project = true to project the initial state "
               "onto the constraints");
    }
  }

  /// [initial] project = true keeps what the scene wrote: given values that no state satisfying
  /// the constraints has are refused (bad input), naming the keys and the constraints violated.
  [[noreturn]] void refuse_given_values(const InconsistentGivenValues& e) const {
    const std::string level = e.velocity_level ? "velocity" : "displacement";
    const auto& values = e.velocity_level ? spec_.initial.velocity : spec_.initial.displacement;
    std::string keys, rows;
    for (int d : e.given) {
      const auto& name = model_.dof_names[static_cast<std::size_t>(d)];
      for (const auto& [given, value] : values) {
        if (given == name) keys += (keys.empty() ? "" : ", ") + name + " = " + fmt(value);
      }
    }
    for (const auto& [row, residual] : e.violated) {
      rows += (rows.empty() ? "'" : ", '") +
              model_.constraints[static_cast<std::size_t>(row)].name + "' (residual " +
              fmt(residual) + ")";
    }
    rows += " at the closest state";
    fail({"initial." + level + "." + model_.dof_names[static_cast<std::size_t>(e.given.front())],
          spec_.initial.where.line},
         "project = true keeps the values given in [initial], but with " + level + " " + keys +
             " kept no initial state satisfies constraint" + (e.violated.size() == 1 ? " " : "s ") +
             rows +
             ": the given values are inconsistent with the constraints; change or "
             "remove one of them");
  }

  /// [initial] project = true: the least-change projection of (u0, v0) onto the constraints,
  /// keeping the values given in [initial].
  void project_initial() {
    if (static_cast<double>(model_.constraint_count()) * model_.dofs() > kMaxDenseEntries) {
      fail(spec_.initial.where, "project = true factors the dense constraint Jacobian: " +
                                    std::to_string(model_.constraint_count()) + " constraints x " +
                                    std::to_string(model_.dofs()) + " DOFs is too large (limit " +
                                    fmt(kMaxDenseEntries) + " entries)");
    }
    const auto s = evaluator();
    const auto n = static_cast<std::size_t>(model_.dofs());
    std::vector<bool> given_u(n, false), given_v(n, false);
    for (const auto& [name, value] : spec_.initial.displacement)
      given_u[static_cast<std::size_t>(model_.dof_index.at(name))] = true;
    for (const auto& [name, value] : spec_.initial.velocity)
      given_v[static_cast<std::size_t>(model_.dof_index.at(name))] = true;
    try {
      report_.initial_projection =
          project_initial_state(*s, 0.0, model_.u0, model_.v0, given_u, given_v, model_.dof_names);
    } catch (const InconsistentGivenValues& e) {
      refuse_given_values(e);
    } catch (const std::runtime_error& e) {
      fail(spec_.initial.where, e.what());
    }
    if (!model_.is_nonlinear()) {  // velocity rows integrate with the projected u(0)
      model_.constraints.clear();
      build_constraints();
    }
  }

  /// [output] energy needs a conservative system (else the energy is not a first integral).
  void check_energy_output() const {
    const auto& q = spec_.output.quantities;
    if (std::find(q.begin(), q.end(), Quantity::energy) == q.end()) return;
    if (!evaluator()->energy(0.0, model_.u0, model_.v0)) {
      fail({"output.quantities", spec_.output.where.line},
           "'energy' needs a conservative scene (no damping, time-independent loads and "
           "constraints): the energy of this one is not conserved, so its error means nothing");
    }
  }

  void check_output() const {
    const double rows = spec_.solve.t_end / spec_.solve.output_step + 1.0;
    if (rows > kMaxOutputRows) {
      fail({"solve.output_step", spec_.solve.where.line},
           "would write " + fmt(rows) + " rows (limit " + fmt(kMaxOutputRows) +
               "): increase output_step");
    }
    check_slaves();
  }

  /// [solve] slaves: one distinct DOF per constraint, each in some constraint (the elimination
  /// solves the constraints for them).
  void check_slaves() const {
    const auto& slaves = spec_.solve.slaves;
    if (slaves.empty()) return;
    const int line = spec_.solve.where.line;
    const auto key = [&](std::size_t k) {
      return SourcePoint{"solve.slaves[" + std::to_string(k + 1) + "]", line};
    };
    std::vector<int> touched(static_cast<std::size_t>(model_.dofs()), 0);
    for (int k = 0; k < model_.A.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(model_.A, k); it; ++it) {
        if (it.value() != 0.0) touched[static_cast<std::size_t>(it.col())] = 1;
      }
    }
    for (std::size_t k = 0; k < slaves.size(); ++k) {
      const int d = dof(slaves[k], key(k));
      for (std::size_t j = 0; j < k; ++j) {
        if (slaves[j] == slaves[k]) {
          fail(key(k), "'" + slaves[k] + "' is named twice (also as solve.slaves[" +
                           std::to_string(j + 1) +
                           "]): each slave is solved from its own constraint");
        }
      }
      if (!touched[static_cast<std::size_t>(d)]) {
        fail(key(k), "'" + slaves[k] +
                         "' appears in no constraint: a slave is a DOF the constraints determine");
      }
    }
    const int m = model_.constraint_count();
    if (static_cast<int>(slaves.size()) != m) {
      fail({"solve.slaves", line},
           "names " + std::to_string(slaves.size()) + " slave" + (slaves.size() == 1 ? "" : "s") +
               " but the scene has " + std::to_string(m) + " constraint" + (m == 1 ? "" : "s") +
               (report_.dropped_constraints.empty() ? "" : " after dropping the redundant ones") +
               ": name exactly one slave per constraint");
    }
    // The elimination solves A_S u_S = g − A_R u_R: the slaves' columns must be well conditioned
    // (the elimination's own limit, 1e12). Dense SVD of m x m; skipped beyond the dense limit.
    if (model_.is_nonlinear() || static_cast<double>(m) * m > kMaxDenseEntries) return;
    const Eigen::MatrixXd a(model_.A);
    Eigen::MatrixXd a_s(m, m);
    std::string names;
    for (int k = 0; k < m; ++k) {
      a_s.col(k) = a.col(model_.dof_index.at(slaves[static_cast<std::size_t>(k)]));
      names += (k ? ", " : "") + slaves[static_cast<std::size_t>(k)];
    }
    const Eigen::BDCSVD<Eigen::MatrixXd> svd(a_s);
    const double smax = svd.singularValues()(0), smin = svd.singularValues()(m - 1);
    constexpr double kMaxSlaveCondition = 1e12;
    if (!(smin > smax / kMaxSlaveCondition)) {
      fail({"solve.slaves", line},
           "the slaves " + names +
               " do not determine the constraints (condition number of their "
               "columns of the constraint matrix " +
               (smin > 0.0 ? fmt(smax / smin) : std::string("infinite")) +
               ", limit 1e12): choose slaves that the constraints fix independently");
    }
  }

  /// The penalty scheme integrates M u'' = f − Aᵀ w (A u − g) with M itself factored: every DOF
  /// needs mass, constrained or not (a massless support included).
  void check_penalty_mass() const {
    std::vector<std::string> massless;
    for (int i = 0; i < model_.dofs(); ++i) {
      if (model_.M.coeff(i, i) == 0.0)
        massless.push_back(model_.dof_names[static_cast<std::size_t>(i)]);
    }
    if (massless.empty()) return;
    std::string names;
    for (std::size_t k = 0; k < massless.size() && k < 10; ++k)
      names += (k ? ", " : "") + massless[k];
    if (massless.size() > 10) names += " ... and " + std::to_string(massless.size() - 10) + " more";
    const bool truss = spec_.model.type == ModelSpec::Type::truss2d ||
                       spec_.model.type == ModelSpec::Type::truss3d;
    fail({truss ? "model.masses" : "model.mass", spec_.model.where.line},
         std::to_string(massless.size()) + " DOF" + (massless.size() == 1 ? "" : "s") + " (" +
             names + ") " + (massless.size() == 1 ? "has" : "have") +
             " no mass: the penalty scheme factors M itself (its constraints are springs), so it "
             "needs mass on every DOF, constrained or not; give them mass or use another scheme");
  }

  /// Accelerations are defined only when M is regular on the motions the constraints allow:
  /// [M Aᵀ; A 0] (and the elimination's Tᵀ M T) is singular exactly when some motion x has
  /// M x = 0 and A x = 0. With M positive semi-definite, a zero diagonal entry means a zero row:
  /// the massless DOFs Z, and the singular motions are the kernel of A restricted to Z. (Massless
  /// DOFs held by stiffness alone are not yet integrated: README "Known limitations".)
  void check_massless_dofs() const {
    const int n = model_.dofs();
    std::vector<int> massless, local(static_cast<std::size_t>(n), -1);
    for (int i = 0; i < n; ++i) {
      if (model_.M.coeff(i, i) == 0.0) {
        local[static_cast<std::size_t>(i)] = static_cast<int>(massless.size());
        massless.push_back(i);
      }
    }
    bool diagonal = true;
    for (int k = 0; k < model_.M.outerSize() && diagonal; ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(model_.M, k); it; ++it) {
        if (it.row() != it.col() && it.value() != 0.0) diagonal = false;
      }
    }
    if (!diagonal) {
      check_singular_mass();
      return;
    }
    if (massless.empty()) return;
    const Eigen::SparseMatrix<double, Eigen::RowMajor> a(model_.A);
    std::vector<int> rows;
    for (int r = 0; r < a.rows(); ++r) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, r); it; ++it) {
        if (local[static_cast<std::size_t>(it.col())] >= 0 && it.value() != 0.0) {
          rows.push_back(r);
          break;
        }
      }
    }
    const auto nz = static_cast<Eigen::Index>(massless.size());
    if (static_cast<double>(rows.size()) * static_cast<double>(nz) > kMaxDenseEntries) return;
    Eigen::MatrixXd az = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), nz);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, rows[k]); it; ++it) {
        const int c = local[static_cast<std::size_t>(it.col())];
        if (c >= 0) az(static_cast<Eigen::Index>(k), c) = it.value();
      }
    }
    std::vector<std::string> free;
    if (rows.empty()) {
      for (int d : massless) free.push_back(model_.dof_names[static_cast<std::size_t>(d)]);
    } else {
      for (Eigen::Index r = 0; r < az.rows(); ++r) {
        const double norm = az.row(r).stableNorm();
        if (norm > 0.0) az.row(r) /= norm;
      }
      Eigen::FullPivLU<Eigen::MatrixXd> lu(az);
      lu.setThreshold(kRankTolerance);
      if (lu.rank() == nz) return;
      const Eigen::MatrixXd kernel = lu.kernel();
      for (Eigen::Index c = 0; c < nz; ++c) {
        if (kernel.row(c).cwiseAbs().maxCoeff() > kRankTolerance) {
          free.push_back(
              model_.dof_names[static_cast<std::size_t>(massless[static_cast<std::size_t>(c)])]);
        }
      }
    }
    std::string names;
    for (std::size_t k = 0; k < free.size() && k < 10; ++k) names += (k ? ", " : "") + free[k];
    if (free.size() > 10) names += " ... and " + std::to_string(free.size() - 10) + " more";
    const bool truss = spec_.model.type == ModelSpec::Type::truss2d ||
                       spec_.model.type == ModelSpec::Type::truss3d;
    fail({truss ? "model.masses" : "model.mass", spec_.model.where.line},
         std::to_string(free.size()) + " DOF" + (free.size() == 1 ? "" : "s") + " (" + names +
             ") ha" + (free.size() == 1 ? "s" : "ve") + " no mass and no constraint fixes " +
             (free.size() == 1 ? "it" : "them") +
             ": the mass matrix is singular on the motions the constraints allow, so the "
             "accelerations are undefined under every scheme (a massless DOF held only by "
             "stiffness is algebraic, which condyn does not integrate yet); give " +
             (truss ? "the node a mass in model.masses" : "the DOF a mass in model.mass") +
             " or constrain it");
  }

  /// A full mass matrix (matrix models, generalized coordinates): its null space N from a dense
  /// eigendecomposition (zero to 1e-12 of its largest eigenvalue, the PSD check's roundoff), and
  /// the motions N y that A N y = 0 leaves free. Skipped beyond the dense limit (the solvers'
  /// own guards remain).
  void check_singular_mass() const {
    const int n = model_.dofs();
    if (static_cast<double>(n) * n > kMaxDenseEntries) return;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(model_.M)};
    const Eigen::VectorXd& lambda = eig.eigenvalues();
    const double largest = lambda.cwiseAbs().maxCoeff();
    std::vector<Eigen::Index> null;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (lambda[k] <= 1e-12 * largest) null.push_back(k);
    }
    if (null.empty()) return;
    Eigen::MatrixXd N(n, static_cast<Eigen::Index>(null.size()));
    for (std::size_t k = 0; k < null.size(); ++k) {
      N.col(static_cast<Eigen::Index>(k)) = eig.eigenvectors().col(null[k]);
    }
    Eigen::MatrixXd motions = N;  // the null motions no constraint holds
    if (model_.constraint_count() > 0) {
      const Eigen::MatrixXd AN = model_.A * N;
      Eigen::FullPivLU<Eigen::MatrixXd> lu(AN);
      lu.setThreshold(kRankTolerance);
      if (lu.rank() == AN.cols()) return;
      motions = N * lu.kernel();
    }
    std::string names;
    int count = 0;
    for (int i = 0; i < n; ++i) {
      if (motions.row(i).cwiseAbs().maxCoeff() <= kRankTolerance) continue;
      if (count < 10) names += (count ? ", " : "") + model_.dof_names[static_cast<std::size_t>(i)];
      ++count;
    }
    if (count > 10) names += " ... and " + std::to_string(count - 10) + " more";
    fail({"model.mass", spec_.model.where.line},
         "the mass matrix is singular along a motion of " + std::to_string(count) + " DOF" +
             (count == 1 ? "" : "s") + " (" + names +
             ") that no constraint holds: the accelerations are undefined under every scheme; "
             "give that motion inertia in model.mass, or constrain it");
  }

  Model build() {
    model_.file = spec_.file;
    model_.name = spec_.name;
    switch (spec_.model.type) {
      case ModelSpec::Type::truss2d:
      case ModelSpec::Type::truss3d:
        build_truss();
        break;
      case ModelSpec::Type::matrix:
        build_matrix();
        break;
      case ModelSpec::Type::sleigh:
        build_sleigh();
        break;
      case ModelSpec::Type::andrews:
      case ModelSpec::Type::car_axis:
      case ModelSpec::Type::pendulum:
        build_benchmark();
        break;
    }
    build_loads();
    build_initial();
    if (!model_.is_nonlinear()) build_constraints();
    if (nonlinear_truss_) finish_point_masses();
    if (spec_.model.type == ModelSpec::Type::sleigh) finish_sleigh();
    check_size();
    if (spec_.initial.project) project_initial();
    // A published reference belongs to the published initial state: a scene that starts the
    // benchmark elsewhere is still a valid model, but no longer that benchmark.
    if (model_.reference && (model_.u0 != base_u0_ || model_.v0 != base_v0_)) {
      model_.reference = nullptr;
      model_.description +=
          " (started from the scene's [initial], not the published state: "
          "no reference)";
    }
    if (model_.is_nonlinear()) linearize();
    check_finite();
    check_magnitudes();
    check_degenerate_dofs();
    while (const auto dependent = check_rank()) drop_constraint(*dependent);
    check_initial_consistency();
    if (spec_.solve.scheme == Scheme::penalty) {
      check_penalty_mass();
    } else {
      check_massless_dofs();
    }
    check_energy_output();
    check_output();
    // Last: the linear system copies the model's final matrices, constraints and loads.
    if (!model_.nonlinear) model_.system = std::make_shared<LinearSystem>(model_);
    return std::move(model_);
  }

 private:
  const SceneSpec& spec_;
  Model model_;
  BuildReport& report_;
  PointMassLayout layout_;
  bool nonlinear_truss_ = false;
  std::vector<SourcePoint> rod_where_;
  Eigen::VectorXd base_u0_, base_v0_;  ///< built-in models' published initial state
};

}  // namespace

Model build_model(const SceneSpec& spec, BuildReport& report) {
  report = {};
  return Builder(spec, report).build();
}

Model build_model(const SceneSpec& spec) {
  BuildReport ignored;
  return build_model(spec, ignored);
}

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

std::vector<double> Model::breakpoints(double t_end) const {
  std::set<double> times;
  for (const auto& l : loads) {
    for (double b : l.value.breakpoints()) {
      if (b < t_end) times.insert(b);
    }
  }
  return {times.begin(), times.end()};
}

}  // namespace condyn
