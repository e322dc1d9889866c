#include "models/assembly/initial_projection.hpp"

#include "models/assembly/least_change.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

namespace condyn {

namespace {

constexpr int kMaxIterations = 50;
// Diagnosis of inconsistent given values: rows that involve no given value are weighted this much
// more, so that the least-squares residual lands on the rows that do (and names them).
constexpr double kHardRowWeight = 1e6;
constexpr int kMaxReportedDofs = 20;
// The largest ratio of the velocity projection's change to the residual it removes
// (Projector::velocity_amplification) taken as a fit: a lever of ratio 10⁴. Positions found to
// the consistency tolerance (1e-10) resolve a double root only to about 1e-5, a ratio of 10⁵.
constexpr double kMaxVelocityGain = 1e4;
// How far off a stalled start the projection starts again on each side, relative to 1 + max|u|
// (Projector::sides).
constexpr double kSideStep = 1e-3;

using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// max_j |a_ij| of every row.
Eigen::VectorXd row_max(const Eigen::SparseMatrix<double>& A) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(A.rows());
  for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      out[it.row()] = std::max(out[it.row()], std::abs(it.value()));
  }
  return out;
}

class Projector {
 public:
  Projector(MechanicalSystem& system, double t, const Eigen::VectorXd& u0,
            const std::vector<bool>& given_u, const std::vector<bool>& given_v)
      : s_(system), t_(t), n_(system.dofs()), m_(system.constraints()) {
    for (int i = 0; i < n_; ++i) {
      if (!given_u[static_cast<std::size_t>(i)]) free_u_.push_back(i);
      if (!given_v[static_cast<std::size_t>(i)]) free_v_.push_back(i);
    }
    for (int i = 0; i < m_; ++i) {
      if (s_.position_rows()[static_cast<std::size_t>(i)]) position_rows_.push_back(i);
    }
    // The structural pattern of every row (explicit zeros included: it does not depend on u).
    const auto& A = s_.constraint_jacobian(t, u0);
    row_dofs_.resize(static_cast<std::size_t>(m_));
    for (int k = 0; k < A.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
        row_dofs_[static_cast<std::size_t>(it.row())].push_back(static_cast<int>(it.col()));
      }
    }
    for (auto& r : row_dofs_) std::sort(r.begin(), r.end());
    // W = diag(M(t, u0)); massless DOFs weigh as the lightest DOF with mass (1 when none has).
    const Eigen::VectorXd d = s_.mass(t, u0).diagonal();
    double lightest = 0.0;
    for (int i = 0; i < n_; ++i) {
      if (d[i] > 0.0 && (lightest == 0.0 || d[i] < lightest)) lightest = d[i];
    }
    if (lightest == 0.0) lightest = 1.0;
    w_inv_sqrt_.resize(n_);
    for (int i = 0; i < n_; ++i) w_inv_sqrt_[i] = 1.0 / std::sqrt(d[i] > 0.0 ? d[i] : lightest);
    hard_given_u_ = row_weights(given_u);
    hard_given_v_ = row_weights(given_v);
  }

  [[nodiscard]] const std::vector<int>& row_dofs(int row) const {
    return row_dofs_[static_cast<std::size_t>(row)];
  }
  /// Row weights for the diagnosis: kHardRowWeight on rows that involve no given value.
  [[nodiscard]] Eigen::VectorXd row_weights(const std::vector<bool>& given) const {
    Eigen::VectorXd w = Eigen::VectorXd::Constant(m_, kHardRowWeight);
    for (int i = 0; i < m_; ++i) {
      for (int d : row_dofs(i)) {
        if (given[static_cast<std::size_t>(d)]) w[i] = 1.0;
      }
    }
    return w;
  }
  [[nodiscard]] const Eigen::VectorXd& hard_rows(bool velocity) const {
    return velocity ? hard_given_v_ : hard_given_u_;
  }

  /// Gauss-Newton on the position rows over the free DOFs; returns the iterations taken.
  int project_positions(Eigen::VectorXd& u, const Eigen::VectorXd& row_weight) const {
    if (position_rows_.empty()) return 0;
    Eigen::VectorXd all(m_);
    int iterations = 0;
    for (; iterations < kMaxIterations; ++iterations) {
      if (violated(u, nullptr).empty()) break;  // met: leave the state as it is, no roundoff moves
      s_.position_residual(t_, u, all);
      const Eigen::VectorXd du = least_change_step(s_.constraint_jacobian(t_, u), position_rows_,
                                                   free_u_, all, row_weight, w_inv_sqrt_);
      u += du;
      if (!u.allFinite()) break;
      if (du.lpNorm<Eigen::Infinity>() <= 1e-14 * (1.0 + u.lpNorm<Eigen::Infinity>())) {
        ++iterations;
        break;
      }
    }
    return iterations;
  }

  /// ψ is affine in v: one least-change step solves it; a second one removes its roundoff.
  void project_velocities(const Eigen::VectorXd& u, Eigen::VectorXd& v,
                          const Eigen::VectorXd& row_weight) const {
    if (m_ == 0) return;
    std::vector<int> rows(static_cast<std::size_t>(m_));
    for (int i = 0; i < m_; ++i) rows[static_cast<std::size_t>(i)] = i;
    Eigen::VectorXd psi(m_);
    const Eigen::SparseMatrix<double> A = s_.constraint_jacobian(t_, u);
    for (int pass = 0; pass < 2; ++pass) {
      if (violated(u, &v).empty()) break;
      s_.velocity_residual(t_, u, v, psi);
      v += least_change_step(A, rows, free_v_, psi, row_weight, w_inv_sqrt_);
    }
  }

  /// Starts where Gauss-Newton stalls because the violated `rows` do not change to first order
  /// along the free DOFs in their patterns: from u displaced by ±kSideStep (1 + max|u|) along
  /// those DOFs, the projections that meet every row, as "uy2 = 0.8" (the DOFs that moved), when
  /// they land on two different states; empty otherwise.
  [[nodiscard]] std::vector<std::string> sides(const Eigen::VectorXd& u,
                                               const std::vector<std::pair<int, double>>& rows,
                                               const std::vector<std::string>& dof_names) const {
    std::vector<bool> free(static_cast<std::size_t>(n_), false), in_rows = free;
    for (int d : free_u_) free[static_cast<std::size_t>(d)] = true;
    for (const auto& [row, r] : rows) {
      for (int d : row_dofs(row))
        in_rows[static_cast<std::size_t>(d)] = free[static_cast<std::size_t>(d)];
    }
    const Eigen::VectorXd plain = Eigen::VectorXd::Ones(m_);
    const double step = kSideStep * (1.0 + u.lpNorm<Eigen::Infinity>());
    std::vector<Eigen::VectorXd> landed;
    for (const double sign : {1.0, -1.0}) {
      Eigen::VectorXd x = u;
      for (int d = 0; d < n_; ++d) {
        if (in_rows[static_cast<std::size_t>(d)]) x[d] += sign * step;
      }
      project_positions(x, plain);
      if (x.allFinite() && violated(x, nullptr).empty()) landed.push_back(x);
    }
    // Both sides met the rows, at two different states (more than the two starts' distance
    // apart: a regular start's two projections land on the same state).
    if (landed.size() != 2 || (landed[0] - landed[1]).lpNorm<Eigen::Infinity>() <= 4.0 * step) {
      return {};
    }
    std::vector<std::string> out;
    for (const Eigen::VectorXd& x : landed) {
      std::ostringstream s;
      s.precision(10);
      int listed = 0;
      for (int d = 0; d < n_ && listed < kMaxReportedDofs; ++d) {
        if (std::abs(x[d] - u[d]) <= 1e-9 * (1.0 + std::abs(u[d]))) continue;
        s << (listed++ ? ", " : "") << dof_names[static_cast<std::size_t>(d)] << " = " << x[d];
      }
      out.push_back(s.str());
    }
    return out;
  }

  /// How far the velocity projection from v moved the free velocities, against the residual it
  /// removed: max|dv| / max_i |ψ_i| / max_j |a_ij| (rows in their own units). About 1 where the
  /// rows set the free velocities directly, k for a lever of ratio k.
  [[nodiscard]] double velocity_amplification(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                              const Eigen::VectorXd& projected) const {
    Eigen::VectorXd psi(m_);
    s_.velocity_residual(t_, u, v, psi);
    const Eigen::VectorXd a_max = row_max(s_.constraint_jacobian(t_, u));
    double residual = 0.0;
    for (int i = 0; i < m_; ++i) {
      if (a_max[i] > 0.0) residual = std::max(residual, std::abs(psi[i]) / a_max[i]);
    }
    const double moved = (projected - v).lpNorm<Eigen::Infinity>();
    return residual > 0.0 ? moved / residual : 0.0;
  }

  /// Rows left violated: position rows at u, or every row at (u, v).
  [[nodiscard]] std::vector<std::pair<int, double>> violated(const Eigen::VectorXd& u,
                                                             const Eigen::VectorXd* v) const {
    std::vector<std::pair<int, double>> out;
    if (m_ == 0) return out;
    Eigen::VectorXd r(m_);
    if (v != nullptr) {
      s_.velocity_residual(t_, u, *v, r);
    } else {
      s_.position_residual(t_, u, r);
    }
    const Eigen::VectorXd a_max = row_max(s_.constraint_jacobian(t_, u));
    const double scale = std::max(1.0, u.lpNorm<Eigen::Infinity>()) *
                         (v ? std::max(1.0, v->lpNorm<Eigen::Infinity>()) : 1.0);
    for (int i = 0; i < m_; ++i) {
      if (v == nullptr && !s_.position_rows()[static_cast<std::size_t>(i)]) continue;
      const double row_size = std::max(1.0, a_max[i]);
      // Negated comparison: a NaN residual is a violation.
      if (!(std::abs(r[i]) <= kConsistencyTolerance * scale * row_size)) out.emplace_back(i, r[i]);
    }
    return out;
  }

 private:
  MechanicalSystem& s_;
  double t_;
  int n_, m_;
  std::vector<int> free_u_, free_v_, position_rows_;
  std::vector<std::vector<int>> row_dofs_;
  Eigen::VectorXd w_inv_sqrt_, hard_given_u_, hard_given_v_;
};

/// The given DOFs the violated rows act on at u (a nonzero coefficient there: a DOF the row
/// depends on but not at this state cannot be the culprit; when none has one, those in the
/// rows' pattern), ascending.
std::vector<int> given_in(MechanicalSystem& s, double t, const Eigen::VectorXd& u,
                          const std::vector<std::pair<int, double>>& rows,
                          const std::vector<bool>& given) {
  const SparseRowMajor A = s.constraint_jacobian(t, u);
  std::set<int> out, in_pattern;
  for (const auto& [row, r] : rows) {
    for (SparseRowMajor::InnerIterator it(A, row); it; ++it) {
      if (!given[static_cast<std::size_t>(it.col())]) continue;
      in_pattern.insert(static_cast<int>(it.col()));
      // Negated: a NaN coefficient (a member of length 0) counts as acting.
      if (!(it.value() == 0.0)) out.insert(static_cast<int>(it.col()));
    }
  }
  // No coefficient on a given DOF at all (a rod whose given ends coincide, its direction 0/0):
  // the given DOFs in the rows' pattern are still the ones that put it there.
  if (out.empty()) out = in_pattern;
  return {out.begin(), out.end()};
}

/// The refusal of a start where the violated `rows` do not change to first order along the free
/// DOFs, with the states on either side (`sides`, from Projector::sides) that meet them.
std::string stalled_start_refusal(const std::vector<std::pair<int, double>>& rows,
                                  const std::vector<std::string>& sides,
                                  const std::vector<std::string>& constraint_names) {
  std::ostringstream s;
  s.precision(10);
  s << "cannot project the initial state: at the given state constraint";
  for (std::size_t k = 0; k < rows.size() && k < 3; ++k) {
    s << (k ? ", '" : (rows.size() == 1 ? " '" : "s '"))
      << constraint_names[static_cast<std::size_t>(rows[k].first)] << "'";
  }
  if (rows.size() > 3) s << " and " << rows.size() - 3 << " more";
  s << (rows.size() == 1 ? " does" : " do")
    << " not change to first order along the DOFs left free, so the least change is not "
       "determined: the constraints are met on either side, e.g. with ";
  for (std::size_t k = 0; k < sides.size(); ++k) s << (k ? " or with " : "") << sides[k];
  s << "; give the one meant in [initial] displacement (project = true keeps it)";
  return s.str();
}

/// What the projection from (u_in, v_in) to (u, v) did, as project_initial_state returns it.
std::string projection_report(const Eigen::VectorXd& u_in, const Eigen::VectorXd& v_in,
                              const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                              const std::vector<bool>& given_u, const std::vector<bool>& given_v,
                              const std::vector<std::string>& dof_names, int iterations) {
  const auto n = static_cast<int>(u.size());
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    kept += static_cast<int>(given_u[static_cast<std::size_t>(i)]) +
            static_cast<int>(given_v[static_cast<std::size_t>(i)]);
  }
  // Moves at the roundoff of the state's size are not reported (a consistent DOF touched by the
  // least-squares solve), only counted.
  const double u_noise =
      4 * std::numeric_limits<double>::epsilon() * std::max(1.0, u.lpNorm<Eigen::Infinity>());
  const double v_noise =
      4 * std::numeric_limits<double>::epsilon() * std::max(1.0, v.lpNorm<Eigen::Infinity>());
  std::vector<std::string> moved;
  int roundoff = 0;
  for (int i = 0; i < n; ++i) {
    const auto& name = dof_names[static_cast<std::size_t>(i)];
    const bool du = std::abs(u[i] - u_in[i]) > u_noise, dv = std::abs(v[i] - v_in[i]) > v_noise;
    roundoff += static_cast<int>(!du && !dv && (u[i] != u_in[i] || v[i] != v_in[i]));
    std::ostringstream line;
    line.precision(10);
    if (du) line << "  " << name << ": displacement " << u_in[i] << " -> " << u[i];
    if (dv) {
      line << (du ? ", velocity " : "  " + name + ": velocity ") << v_in[i] << " -> " << v[i];
    }
    if (du || dv) moved.push_back(line.str());
  }
  std::ostringstream s;
  s.precision(3);
  if (moved.empty()) {
    s << "[initial] project = true: the initial state already satisfies the constraints"
      << (roundoff > 0 ? " (to roundoff)" : "") << "; nothing moved";
    return s.str();
  }
  s << "projected onto the constraints, keeping the " << kept << " value" << (kept == 1 ? "" : "s")
    << " given in [initial]\n  moved " << moved.size() << " DOF" << (moved.size() == 1 ? "" : "s")
    << " by the least mass-weighted change (" << iterations << " Gauss-Newton iteration"
    << (iterations == 1 ? "" : "s") << "):";
  for (std::size_t k = 0; k < moved.size() && k < kMaxReportedDofs; ++k) s << "\n" << moved[k];
  if (moved.size() > kMaxReportedDofs) {
    s << "\n  ... and " << moved.size() - kMaxReportedDofs << " more DOFs";
  }
  if (roundoff > 0) s << "\n  (" << roundoff << " more by roundoff only)";
  return s.str();
}

}  // namespace

std::string project_initial_state(MechanicalSystem& system, double t, Eigen::VectorXd& u,
                                  Eigen::VectorXd& v, const std::vector<bool>& given_u,
                                  const std::vector<bool>& given_v,
                                  const std::vector<std::string>& dof_names,
                                  const std::vector<std::string>& constraint_names) {
  const int m = system.constraints();
  const Eigen::VectorXd u_in = u, v_in = v;
  const Projector p(system, t, u_in, given_u, given_v);
  const Eigen::VectorXd plain = Eigen::VectorXd::Ones(m);

  // Inconsistent: diagnose with the rows that involve no given value held (nearly) exactly, so
  // the residual is reported on the rows that do; name the given values there.
  const auto refuse = [&](bool velocity, const std::vector<std::pair<int, double>>& first) {
    Eigen::VectorXd uu = u_in, vv = v_in;
    p.project_positions(uu, velocity ? plain : p.hard_rows(false));
    if (velocity) p.project_velocities(uu, vv, p.hard_rows(true));
    auto rows = p.violated(uu, velocity ? &vv : nullptr);
    if (rows.empty()) rows = first;
    const auto& given = velocity ? given_v : given_u;
    std::vector<int> named = given_in(system, t, uu, rows, given);
    if (named.empty()) {  // the constraints alone cannot be met (or the diagnosis moved them)
      named = given_in(system, t, uu, first, given);
      if (named.empty()) return;  // not the given values: the caller's generic message
      rows = first;
    }
    throw InconsistentGivenValues("the given initial values are inconsistent", velocity, rows,
                                  named);
  };

  const int iterations = p.project_positions(u, plain);
  if (const auto bad = p.violated(u, nullptr); !bad.empty() || !u.allFinite()) {
    // A start where the rows do not change to first order along some free DOFs (a rod given its
    // x and left its y at 0: the closest states lie at ±y): Gauss-Newton cannot leave it, and
    // which side is meant is not the projection's to choose. Found by starting again a little
    // off, on each side, along the free DOFs of the violated rows.
    const auto start_rows = p.violated(u_in, nullptr);
    const auto sides = p.sides(u_in, start_rows, dof_names);
    if (!sides.empty()) {
      throw std::runtime_error(stalled_start_refusal(start_rows, sides, constraint_names));
    }
    refuse(false, bad);
    std::ostringstream s;
    s << "cannot project the initial state: Gauss-Newton did not converge in " << kMaxIterations
      << " iterations (no configuration near the given one satisfies the constraints)";
    throw std::runtime_error(s.str());
  }
  // Velocities the rows barely depend on where the positions landed: those that meet them are
  // the residual over that small rate. A pendulum written horizontal, given uy2 = -1 (straight
  // down: a double root, found to about √tol, ux2 = -0.99999237) and vy2 = 1, got vx2 = 131072
  // and an exit 0; at the exact configuration no velocity meets the
  // given speed.
  Eigen::VectorXd projected = v;
  p.project_velocities(u, projected, plain);
  if (const double gain = p.velocity_amplification(u, v, projected); gain > kMaxVelocityGain) {
    std::ostringstream s;
    s.precision(3);
    s << "cannot project the initial velocities: where the positions meet the constraints, the "
         "rows barely depend on the velocities left free (meeting them moves those "
      << gain
      << " times the rows' residual: a singular configuration, or next to one), so the given "
         "velocities do not fit this configuration; change them, or give displacements away "
         "from it";
    throw std::runtime_error(s.str());
  }
  v = projected;
  if (const auto bad = p.violated(u, &v); !bad.empty() || !v.allFinite()) {
    refuse(true, bad);
    throw std::runtime_error(
        "cannot project the initial velocities: the constraints are dependent (singular) at the "
        "projected configuration, and no velocity satisfies them all");
  }

  return projection_report(u_in, v_in, u, v, given_u, given_v, dof_names, iterations);
}

}  // namespace condyn
