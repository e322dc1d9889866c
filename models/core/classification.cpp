#include "models/core/classification.hpp"

#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

namespace condyn {

std::string ConstraintClass::holonomy() const {
  if (!velocity_level) return "holonomic";
  return integrable ? "pseudo-nonholonomic (integrable)" : "nonholonomic";
}

namespace {

/// Frobenius test of one velocity row a(u)·u' = 0 at u: the row is integrable near u only if
/// the 3-form a ∧ da vanishes, i.e. a_i (∂_j a_k − ∂_k a_j) + cyclic = 0 for all i < j < k
/// (for n = 3: a · (∇ × a) = 0). Returns the largest |component| (0 when fewer than 3 DOFs take
/// part). Only the DOFs where a or its derivative D(k, l) = ∂a_k/∂u_l has an entry take part: a
/// term with any other index is zero, so the test costs the row's size cubed, not the model's.
double frobenius_defect(MechanicalSystem& s, int row, const Eigen::VectorXd& u) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(s.constraints());
  w[row] = 1.0;
  const Eigen::SparseMatrix<double> D = s.constraint_force_jacobian(0.0, u, w);
  if (D.size() == 0) return 0.0;  // constant coefficients: integrable
  // The DOFs taking part, ascending (the sums below then add in the order they always did).
  std::vector<bool> in(static_cast<std::size_t>(s.dofs()), false);
  const auto& A = s.constraint_jacobian(0.0, u);
  Eigen::VectorXd a_full = Eigen::VectorXd::Zero(s.dofs());
  for (int col = 0; col < A.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
      if (it.row() == row) {
        in[static_cast<std::size_t>(it.col())] = true;
        a_full[it.col()] += it.value();
      }
    }
  }
  for (int col = 0; col < D.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(D, col); it; ++it) {
      in[static_cast<std::size_t>(it.row())] = in[static_cast<std::size_t>(it.col())] = true;
    }
  }
  std::vector<int> part;                                           // index -> DOF
  std::vector<int> local(static_cast<std::size_t>(s.dofs()), -1);  // DOF -> index
  for (int d = 0; d < s.dofs(); ++d) {
    if (!in[static_cast<std::size_t>(d)]) continue;
    local[static_cast<std::size_t>(d)] = static_cast<int>(part.size());
    part.push_back(d);
  }
  const auto p = static_cast<Eigen::Index>(part.size());
  Eigen::MatrixXd Dp = Eigen::MatrixXd::Zero(p, p);
  for (int col = 0; col < D.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(D, col); it; ++it) {
      Dp(local[static_cast<std::size_t>(it.row())], local[static_cast<std::size_t>(it.col())]) +=
          it.value();
    }
  }
  Eigen::VectorXd a(p);
  for (Eigen::Index i = 0; i < p; ++i) a[i] = a_full[part[static_cast<std::size_t>(i)]];
  const auto da = [&](Eigen::Index j, Eigen::Index k) { return Dp(k, j) - Dp(j, k); };
  double worst = 0.0;
  for (Eigen::Index i = 0; i < p; ++i) {
    for (Eigen::Index j = i + 1; j < p; ++j) {
      for (Eigen::Index k = j + 1; k < p; ++k) {
        worst = std::max(worst, std::abs(a[i] * da(j, k) + a[j] * da(k, i) + a[k] * da(i, j)));
      }
    }
  }
  return worst;
}

/// For every row of A(t, u), the DOFs it depends on: pattern entries that are nonzero (or not
/// finite) at u0 or at three states around it, u0 + δ_k with δ_k,i = 0.1 (1 + |u0_i|)
/// sin(1.7 i + k): an entry that is not identically zero vanishes at all four only by
/// coincidence. Four evaluations of A for all rows together, each row's DOFs ascending.
std::vector<std::vector<int>> dependent_dofs(MechanicalSystem& s, const Eigen::VectorXd& u0) {
  const auto n = static_cast<Eigen::Index>(s.dofs());
  Eigen::SparseMatrix<double> seen;  // |A| summed over the states: nonzero where A ever was
  for (int k = 0; k < 4; ++k) {
    Eigen::VectorXd u = u0;
    for (Eigen::Index i = 0; k > 0 && i < n; ++i) {
      u[i] += 0.1 * (1.0 + std::abs(u0[i])) * std::sin(1.7 * static_cast<double>(i) + k);
    }
    // A NaN entry marks its DOF as a nonzero does (NaN != 0), so map it to 1, not to NaN's abs.
    const Eigen::SparseMatrix<double> marked =
        s.constraint_jacobian(0.0, u).unaryExpr([](double v) { return v != 0.0 ? 1.0 : 0.0; });
    if (k == 0) {
      seen = marked;
    } else {
      seen += marked;
    }
  }
  std::vector<std::vector<int>> out(static_cast<std::size_t>(s.constraints()));
  for (int col = 0; col < seen.outerSize(); ++col) {  // columns ascending: DOFs in order
    for (Eigen::SparseMatrix<double>::InnerIterator it(seen, col); it; ++it) {
      if (it.value() != 0.0) out[static_cast<std::size_t>(it.row())].push_back(col);
    }
  }
  return out;
}

/// What the nonlinear rows share: one evaluator, the rows' DOFs, and the residuals at two times
/// with the same state, each evaluated once for every row (per row, they made `info` quadratic
/// in the rows).
struct NonlinearProbe {
  std::unique_ptr<MechanicalSystem> system;
  std::vector<std::vector<int>> dofs;
  Eigen::VectorXd phi0, phi1, psi0, psi1;  ///< at t = 0 and at t1
};

NonlinearProbe probe_nonlinear(const Model& model, double t_end) {
  NonlinearProbe p;
  p.system = model.evaluator();
  MechanicalSystem& s = *p.system;
  p.dofs = dependent_dofs(s, model.u0);
  const int m = model.constraint_count();
  const double t1 = 0.5 * t_end + 0.1234;
  p.phi0.resize(m);
  p.phi1.resize(m);
  p.psi0.resize(m);
  p.psi1.resize(m);
  s.velocity_residual(0.0, model.u0, model.v0, p.psi0);
  s.velocity_residual(t1, model.u0, model.v0, p.psi1);
  s.position_residual(0.0, model.u0, p.phi0);
  s.position_residual(t1, model.u0, p.phi1);
  return p;
}

/// Nonlinear rows: time dependence from the residuals at two times with the same state;
/// integrability by the Frobenius test.
ConstraintClass classify_nonlinear(const Model& model, int row, NonlinearProbe& p) {
  const auto& c = model.constraints[static_cast<std::size_t>(row)];
  const auto r = static_cast<Eigen::Index>(row);
  ConstraintClass k;
  k.name = c.name;
  k.linear = false;
  k.velocity_level = c.level == ConstraintLevel::velocity;
  // The DOFs the row depends on: those where ∂φ/∂u is not identically zero. A value at u0 may
  // vanish by accident (the knife edge's -sin(theta) at theta = 0), and the stored pattern may
  // hold more than the row uses (small dense blocks keep every entry: Andrews, the car axis). So:
  // the entries of the pattern that are nonzero at u0 or at one of a few states around it.
  for (int d : p.dofs[static_cast<std::size_t>(row)]) {
    k.dofs.push_back(model.dof_names[static_cast<std::size_t>(d)]);
  }
  k.single_freedom = k.dofs.size() == 1;
  // Exact comparison on purpose: any change with t alone is time dependence.
  k.rheonomic = p.psi0[r] != p.psi1[r] || p.phi0[r] != p.phi1[r];
  k.homogeneous = !k.rheonomic;
  std::ostringstream note;
  note.precision(3);
  note << c.nonlinear_kind;
  if (k.velocity_level) {
    const double defect = frobenius_defect(*p.system, row, model.u0);
    k.integrable = !c.nonholonomic && defect == 0.0;
    note << "; Frobenius a·(curl a) test at u0: " << defect
         << (defect != 0.0 ? " != 0, not integrable" : " (no obstruction found)");
  }
  k.note = note.str();
  return k;
}

}  // namespace

std::vector<ConstraintClass> classify_constraints(const Model& model, double t_end) {
  std::vector<ConstraintClass> out;
  out.reserve(model.constraints.size());
  std::optional<NonlinearProbe> probe;  // made at the first nonlinear row, for all of them
  for (const auto& c : model.constraints) {
    if (!c.nonlinear_kind.empty()) {
      if (!probe) probe = probe_nonlinear(model, t_end);
      out.push_back(classify_nonlinear(model, static_cast<int>(out.size()), *probe));
      continue;
    }
    ConstraintClass k;
    k.name = c.name;
    k.single_freedom = c.coefficients.size() == 1;
    k.velocity_level = c.level == ConstraintLevel::velocity;
    // A linear velocity constraint with constant coefficients, a·u' = h(t), integrates to
    // a·u = a·u(0) + ∫h (§5.5.3): every velocity constraint a scene can state today is integrable.
    k.integrable = true;
    // Time dependence and homogeneity refer to the position-level (integrated) form; the chapter
    // counts every rheonomic constraint as nonhomogeneous (§5.3.2).
    k.rheonomic = !c.position_value.is_constant();
    k.homogeneous = !k.rheonomic && c.position_value.is_zero();
    k.linear = true;
    for (const auto& [d, a] : c.coefficients)
      k.dofs.push_back(model.dof_names[static_cast<std::size_t>(d)]);
    out.push_back(std::move(k));
  }
  return out;
}

}  // namespace condyn
