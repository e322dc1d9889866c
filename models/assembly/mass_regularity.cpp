// The mass matrix on the motions the constraints allow: regular, so the accelerations are defined.

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <string>
#include <vector>

#include "models/assembly/model_builder.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/massless_dofs.hpp"
#include "models/core/row_scales.hpp"

namespace condyn {

namespace {

/// The names of `dofs`: the first ten, then how many more.
std::string first_names(const std::vector<std::string>& names, const std::vector<int>& dofs) {
  constexpr std::size_t kShown = 10;
  std::string s;
  for (std::size_t k = 0; k < dofs.size() && k < kShown; ++k)
    s += (k ? ", " : "") + names[static_cast<std::size_t>(dofs[k])];
  if (dofs.size() > kShown) s += " ... and " + std::to_string(dofs.size() - kShown) + " more";
  return s;
}

}  // namespace

/// Accelerations are defined only when M is regular on the motions the constraints allow:
/// [M Aᵀ; A 0] (and the elimination's Tᵀ M T) is singular exactly when some motion x has
/// M x = 0 and A x = 0. With M positive semi-definite, a zero diagonal entry means a zero row:
/// the massless DOFs Z, and the singular motions are the kernel of A restricted to Z. Massless DOFs
/// that no constraint touches but stiffness (or damping) holds are algebraic unknowns the DAE
/// formulations integrate (dae/interface/held_massless.hpp): they are left out here, on linear
/// models. A value [initial] gives a massless DOF held by stiffness is not kept where the DOF has
/// no state of its own: without damping, its displacement and velocity are set at every instant, t
/// = 0 included, by its stiffness rows; with damping (first order), its velocity is.
void ModelBuilder::warn_given_held_values(const std::vector<bool>& held) {
  for (const auto* given : {&spec_.initial.displacement, &spec_.initial.velocity}) {
    const bool displacement = given == &spec_.initial.displacement;
    for (const auto& [name, value] : *given) {
      const auto it = std::find(model_.dof_names.begin(), model_.dof_names.end(), name);
      if (it == model_.dof_names.end()) continue;
      const auto d = static_cast<std::size_t>(it - model_.dof_names.begin());
      if (!held[d]) continue;
      // First order (c_hh != 0, models/core/massless_dofs.hpp): its displacement is a state.
      const bool damped =
          model_.has_damping() &&
          model_.C.coeff(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(d)) != 0.0;
      if (displacement && damped) continue;
      report_.warnings.push_back(
          std::string("[initial] ") + (displacement ? "displacement" : "velocity") + " gives " +
          name + " = " + fmt(value) + ", but " + name + " has no mass" +
          (damped ? ": its damping and stiffness rows set its velocity"
                  : " nor damping: its stiffness rows set it") +
          " at every instant, t = 0 included, so the value given is not kept (the output's first "
          "row shows the one used)");
    }
  }
}

/// The one line `run` and `info` print of every DOF without mass (a zero diagonal entry of M),
/// those in constraints and those that only their stiffness or damping holds: a mass forgotten
/// on a DOF that its stiffness holds makes a valid model, so the run says which DOFs it treats
/// as massless (issue 42: a roof without its mass ran silently).
void ModelBuilder::report_massless_dofs(const std::vector<bool>& held) {
  std::vector<int> massless;
  long in_constraints = 0, by_stiffness = 0, by_damping = 0;
  for (int i = 0; i < model_.dofs(); ++i) {
    if (model_.M.coeff(i, i) != 0.0) continue;
    massless.push_back(i);
    if (held[static_cast<std::size_t>(i)]) {
      // First order through damping of its own (models/core/massless_dofs.hpp), else algebraic.
      ++(model_.has_damping() && model_.C.coeff(i, i) != 0.0 ? by_damping : by_stiffness);
    } else if (model_.constraint_count() > 0 && model_.A.col(i).nonZeros() > 0) {
      ++in_constraints;
    }
  }
  if (massless.empty()) return;
  std::string parts;
  const auto add = [&parts](long count, const std::string& what) {
    if (count > 0) parts += (parts.empty() ? "" : ", ") + std::to_string(count) + " " + what;
  };
  add(in_constraints, "in constraints");
  add(by_stiffness, std::string(by_stiffness == 1 ? "held by its" : "held by their") +
                        " stiffness alone (algebraic, no inertia)");
  add(by_damping, std::string(by_damping == 1 ? "held by its" : "held by their") +
                      " stiffness and damping alone (first order, no inertia)");
  report_.massless_dofs = std::to_string(massless.size()) + " of " + std::to_string(model_.dofs()) +
                          " (" + first_names(model_.dof_names, massless) + ")" +
                          (parts.empty() ? "" : ": " + parts);
}

void ModelBuilder::check_massless_dofs() {
  const int n = model_.dofs();
  std::vector<bool> held = held_massless();
  warn_given_held_values(held);
  report_massless_dofs(held);
  std::vector<int> massless, local(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    if (model_.M.coeff(i, i) == 0.0 && !held[static_cast<std::size_t>(i)]) {
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
    check_singular_mass(held);
    return;
  }
  if (massless.empty()) return;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> a(model_.A);
  std::vector<int> rows;
  std::vector<bool> touched(massless.size(), false);  // by a nonzero of some constraint row
  for (int r = 0; r < a.rows(); ++r) {
    bool on_massless = false;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, r); it; ++it) {
      const int c = local[static_cast<std::size_t>(it.col())];
      if (c >= 0 && it.value() != 0.0) {
        on_massless = true;
        touched[static_cast<std::size_t>(c)] = true;
      }
    }
    if (on_massless) rows.push_back(r);
  }
  const auto nz = static_cast<Eigen::Index>(massless.size());
  std::vector<std::string> free;
  if (static_cast<double>(rows.size()) * static_cast<double>(nz) > kMaxDenseEntries) {
    // Beyond the dense kernel: a massless DOF in no constraint is certainly free (named below);
    // whether the rows on the others are independent enough to hold them all is not worked out.
    for (std::size_t c = 0; c < massless.size(); ++c) {
      if (!touched[c]) free.push_back(model_.dof_names[static_cast<std::size_t>(massless[c])]);
    }
    if (free.empty()) {
      report_.warnings.push_back(std::to_string(nz) +
                                 " DOFs have no mass; every one appears in a constraint, but at " +
                                 std::to_string(rows.size()) +
                                 " such constraints condyn does not check that they hold "
                                 "all of them (a run fails if they do not)");
      return;
    }
  }
  if (rows.empty()) {
    for (int d : massless) free.push_back(model_.dof_names[static_cast<std::size_t>(d)]);
  } else if (free.empty()) {  // within the dense kernel (beyond it, `free` is filled above)
    Eigen::MatrixXd az = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), nz);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, rows[k]); it; ++it) {
        const int c = local[static_cast<std::size_t>(it.col())];
        if (c >= 0) az(static_cast<Eigen::Index>(k), c) = it.value();
      }
    }
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
  const bool truss =
      spec_.model.type == ModelSpec::Type::truss2d || spec_.model.type == ModelSpec::Type::truss3d;
  fail({truss ? "model.masses" : "model.mass", spec_.model.where.line},
       std::to_string(free.size()) + " DOF" + (free.size() == 1 ? "" : "s") + " (" + names +
           ") ha" + (free.size() == 1 ? "s" : "ve") + " no mass and no constraint fixes " +
           (free.size() == 1 ? "it" : "them") +
           ": the mass matrix is singular on the motions the constraints allow, which condyn's "
           "schemes cannot integrate (a massless DOF that no constraint touches is integrated "
           "when its stiffness holds it; one in a constraint must be fixed by the constraints: "
           "docs/limitations.md); give " +
           (truss ? "the node a mass in model.masses" : "the DOF a mass in model.mass") +
           " or constrain it");
}

/// The massless DOFs that no constraint touches and whose stiffness or damping holds them (a
/// nonzero diagonal entry of K or C, and a regular block: models/core/massless_dofs.hpp), on a
/// linear model: algebraic unknowns the DAE formulations integrate. Those that nothing holds are
/// left to check_massless_dofs; the other cases are refused here, DOFs named.
std::vector<bool> ModelBuilder::held_massless() const {
  const int n = model_.dofs();
  std::vector<bool> held(static_cast<std::size_t>(n), false);
  const Eigen::SparseMatrix<double> none;
  const HeldDofs dofs =
      held_massless_dofs(model_.M, model_.has_damping() ? model_.C : none, *model_.K, model_.A);
  const bool truss =
      spec_.model.type == ModelSpec::Type::truss2d || spec_.model.type == ModelSpec::Type::truss3d;
  const SourcePoint where{truss ? "model.masses" : "model.mass", spec_.model.where.line};
  const auto named = [&](std::vector<int> list) {
    std::sort(list.begin(), list.end());
    return std::to_string(list.size()) + " DOF" + (list.size() == 1 ? " (" : "s (") +
           first_names(model_.dof_names, list) + ") ha" + (list.size() == 1 ? "s" : "ve");
  };
  std::vector<int> all = dofs.undamped;
  all.insert(all.end(), dofs.damped.begin(), dofs.damped.end());
  all.insert(all.end(), dofs.coupled.begin(), dofs.coupled.end());
  if (all.empty()) return held;
  if (model_.is_nonlinear()) {
    fail(where, named(all) +
                    " no mass and no constraint: massless DOFs held by stiffness are integrated on "
                    "linear models only (small displacements), and this model is nonlinear; give "
                    "them mass or constrain them");
  }
  if (!dofs.coupled.empty()) {
    fail(where, named(dofs.coupled) +
                    " no mass, no constraint and no damping of their own (c_hh = 0) but damping "
                    "coupling to other DOFs: their momentum rows are neither algebraic nor first "
                    "order; give them mass, damping or no damping coupling");
  }
  if (const auto why = singular_held_block(dofs, model_.C, *model_.K)) {
    std::vector<int> massless = dofs.undamped;
    massless.insert(massless.end(), dofs.damped.begin(), dofs.damped.end());
    fail(where, named(massless) + " no mass and no constraint, and " + *why +
                    " that neither a mass nor a constraint holds; give them mass or constrain "
                    "them");
  }
  for (int j : dofs.undamped) held[static_cast<std::size_t>(j)] = true;
  for (int j : dofs.damped) held[static_cast<std::size_t>(j)] = true;
  return held;
}

/// A full mass matrix (matrix models, generalized coordinates): its null space N from a dense
/// eigendecomposition (zero to 1e-12 of its largest eigenvalue, the PSD check's roundoff), and
/// the motions N y that A N y = 0 leaves free. Beyond the dense limit, a sparse LDLᵀ of M: pivots
/// all above 1e-12 of the largest say M is positive definite (nothing to check); otherwise M may
/// be singular and a warning says the check of the constraints that hold it was not made.
void ModelBuilder::check_singular_mass(const std::vector<bool>& held) {
  const int n = model_.dofs();
  // The held massless DOFs' rows and columns of M are zero: a unit mass there removes exactly
  // their null directions, which their stiffness holds.
  Eigen::SparseMatrix<double> mass = model_.M;
  {
    Eigen::SparseMatrix<double> unit(n, n);
    for (int i = 0; i < n; ++i) {
      if (held[static_cast<std::size_t>(i)]) unit.insert(i, i) = 1.0;
    }
    mass += unit;
  }
  if (static_cast<double>(n) * n > kMaxDenseEntries) {
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(mass);
    const Eigen::VectorXd d = ldlt.vectorD();
    if (ldlt.info() == Eigen::Success && d.size() == n && d.minCoeff() > 1e-12 * d.maxCoeff())
      return;
    report_.warnings.push_back(
        "the mass matrix may be singular or indefinite (a sparse LDLt pivot at or below 1e-12 of "
        "the largest); "
        "at " +
        std::to_string(n) +
        " DOFs condyn does not check which motions the constraints leave without inertia, and "
        "a run fails if one exists");
    return;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(mass)};
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
    // A N with A's rows scaled first (row_scales): a row written at 1e-150 holds a motion as well
    // as one written at 1, and LU's threshold is relative to the largest pivot.
    const Eigen::SparseMatrix<double> scaled = row_scales(model_.A).asDiagonal() * model_.A;
    const Eigen::MatrixXd AN = scaled * N;
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

}  // namespace condyn
