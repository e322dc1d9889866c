#include "models/classification.hpp"

#include <cmath>
#include <sstream>

namespace condyn {

std::string ConstraintClass::holonomy() const {
  if (!velocity_level) return "holonomic";
  return integrable ? "pseudo-nonholonomic (integrable)" : "nonholonomic";
}

namespace {

/// Frobenius test of one velocity row a(u)·u' = 0 at u: the row is integrable near u only if
/// the 3-form a ∧ da vanishes, i.e. a_i (∂_j a_k − ∂_k a_j) + cyclic = 0 for all i < j < k
/// (for n = 3: a · (∇ × a) = 0). Returns the largest |component| (0 when n < 3).
double frobenius_defect(MechanicalSystem& s, int row, const Eigen::VectorXd& u) {
  const int n = s.dofs();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(s.constraints());
  w[row] = 1.0;
  const Eigen::MatrixXd D(s.constraint_force_jacobian(0.0, u, w));  // D(k, l) = ∂a_k/∂u_l
  if (D.size() == 0) return 0.0;  // constant coefficients: integrable
  const Eigen::VectorXd a = Eigen::MatrixXd(s.constraint_jacobian(0.0, u)).row(row).transpose();
  const auto da = [&](int j, int k) { return D(k, j) - D(j, k); };  // ∂_j a_k − ∂_k a_j
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int k = j + 1; k < n; ++k) {
        worst = std::max(worst, std::abs(a[i] * da(j, k) + a[j] * da(k, i) + a[k] * da(i, j)));
      }
    }
  }
  return worst;
}

/// The DOFs row `row` of A(t, u) depends on: pattern entries that are nonzero (or not finite) at
/// u0 or at three states around it, u0 + δ_k with δ_k,i = 0.1 (1 + |u0_i|) sin(1.7 i + k): an
/// entry that is not identically zero vanishes at all four only by coincidence.
std::vector<int> dependent_dofs(MechanicalSystem& s, int row, const Eigen::VectorXd& u0) {
  const auto n = static_cast<Eigen::Index>(s.dofs());
  std::vector<bool> on(static_cast<std::size_t>(n), false);
  for (int k = 0; k < 4; ++k) {
    Eigen::VectorXd u = u0;
    for (Eigen::Index i = 0; k > 0 && i < n; ++i) {
      u[i] += 0.1 * (1.0 + std::abs(u0[i])) * std::sin(1.7 * static_cast<double>(i) + k);
    }
    const auto& A = s.constraint_jacobian(0.0, u);
    for (int col = 0; col < A.outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
        if (it.row() == row && it.value() != 0.0) on[static_cast<std::size_t>(it.col())] = true;
      }
    }
  }
  std::vector<int> out;
  for (Eigen::Index d = 0; d < n; ++d) {
    if (on[static_cast<std::size_t>(d)]) out.push_back(static_cast<int>(d));
  }
  return out;
}

/// Nonlinear rows: time dependence probed by evaluating the residuals at two times with the same
/// state; integrability by the Frobenius test.
ConstraintClass classify_nonlinear(const Model& model, int row, double t_end) {
  const auto& c = model.constraints[static_cast<std::size_t>(row)];
  const auto evaluator = model.evaluator();
  MechanicalSystem& s = *evaluator;
  ConstraintClass k;
  k.name = c.name;
  k.linear = false;
  k.velocity_level = c.level == ConstraintSpec::Level::velocity;
  // The DOFs the row depends on: those where ∂φ/∂u is not identically zero. A value at u0 may
  // vanish by accident (the knife edge's -sin(theta) at theta = 0), and the stored pattern may
  // hold more than the row uses (small dense blocks keep every entry: Andrews, the car axis). So:
  // the entries of the pattern that are nonzero at u0 or at one of a few states around it.
  for (int d : dependent_dofs(s, row, model.u0)) {
    k.dofs.push_back(model.dof_names[static_cast<std::size_t>(d)]);
  }
  k.single_freedom = k.dofs.size() == 1;
  const int m = model.constraint_count();
  Eigen::VectorXd r0(m), r1(m);
  const double t1 = 0.5 * t_end + 0.1234;
  s.velocity_residual(0.0, model.u0, model.v0, r0);
  s.velocity_residual(t1, model.u0, model.v0, r1);
  k.rheonomic = r0[row] != r1[row];
  s.position_residual(0.0, model.u0, r0);
  s.position_residual(t1, model.u0, r1);
  k.rheonomic = k.rheonomic || r0[row] != r1[row];
  k.homogeneous = !k.rheonomic;
  std::ostringstream note;
  note.precision(3);
  note << c.nonlinear_kind;
  if (k.velocity_level) {
    const double defect = frobenius_defect(s, row, model.u0);
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
  for (const auto& c : model.constraints) {
    if (!c.nonlinear_kind.empty()) {
      out.push_back(classify_nonlinear(model, static_cast<int>(out.size()), t_end));
      continue;
    }
    ConstraintClass k;
    k.name = c.name;
    k.single_freedom = c.coefficients.size() == 1;
    k.velocity_level = c.level == ConstraintSpec::Level::velocity;
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
