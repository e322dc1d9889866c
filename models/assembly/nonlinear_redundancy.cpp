// [solve] redundant = "drop" on a nonlinear model: whether rows dependent at t = 0 are redundant
// or only singular there, and the system restricted to the rows kept.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "models/assembly/model_builder.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/systems/row_subset_outputs.hpp"
#include "models/systems/row_subset_system.hpp"

namespace condyn {

namespace {

// Rows dependent everywhere along the motion (redundant) keep their combination at second order:
// sum_k w_k γ_k = 0 for every admissible velocity. The weights hold to the rank tolerance 1e-10
// (the rows are dependent to that), times the conditioning of the rows that span the dependent
// one: 1e-6 of the terms' size leaves that a margin of 1e4, while a singular configuration
// leaves a mismatch of the terms' own size (the rows part along the motion at first order).
constexpr double kSecondOrderTolerance = 1e-6;

/// A velocity the rows of `at` (DOFs x rows, its columns the rows) allow, v·row = 0 for each: a
/// fixed combination of the directions their QR leaves free, of largest entry 1 (0 when none
/// is free). Fixed, so that a build decides the same way every time; not special to any scene.
Eigen::VectorXd free_motion(const Eigen::MatrixXd& at) {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(at.rows(), at.cols());
  qr.setThreshold(kRankTolerance);
  qr.compute(at);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(at.rows());
  for (Eigen::Index i = qr.rank(); i < at.rows(); ++i) {
    e[i] = std::cos(0.7 + 1.3 * static_cast<double>(i));
  }
  Eigen::VectorXd z = qr.householderQ() * e;
  const double largest = z.lpNorm<Eigen::Infinity>();
  if (largest > 0.0) z /= largest;
  return z;
}

/// A velocity the system's rows `rows` allow at t = 0 that moves the DOFs the rows `group` reach:
/// zero outside those DOFs, and free_motion() on the rows' entries there (a row reaching them and
/// others must hold on their part alone). Read from `jac`, the system's Jacobian with its stored
/// zeros: a rod along x at t = 0 stores its y entries as 0, and the motion along y is the one that
/// parts a singular set. Nothing when the block is too large to factor densely.
std::optional<Eigen::VectorXd> free_velocity(
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& jac, const std::vector<int>& group,
    const std::vector<int>& rows) {
  using RowIterator = Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator;
  std::vector<int> local(static_cast<std::size_t>(jac.cols()), -1);
  std::vector<int> dofs;
  for (const int r : group) {
    for (RowIterator it(jac, r); it; ++it) {
      auto& l = local[static_cast<std::size_t>(it.col())];
      if (l < 0) {
        l = static_cast<int>(dofs.size());
        dofs.push_back(static_cast<int>(it.col()));
      }
    }
  }
  std::vector<int> reaching;
  for (const int r : rows) {
    for (RowIterator it(jac, r); it; ++it) {
      if (local[static_cast<std::size_t>(it.col())] >= 0) {
        reaching.push_back(r);
        break;
      }
    }
  }
  const auto nd = static_cast<Eigen::Index>(dofs.size());
  const auto nr = static_cast<Eigen::Index>(reaching.size());
  if (static_cast<double>(nd) * static_cast<double>(nr) > kMaxDenseEntries) return std::nullopt;
  Eigen::MatrixXd at = Eigen::MatrixXd::Zero(nd, nr);
  for (Eigen::Index c = 0; c < nr; ++c) {
    for (RowIterator it(jac, reaching[static_cast<std::size_t>(c)]); it; ++it) {
      const int l = local[static_cast<std::size_t>(it.col())];
      if (l >= 0) at(l, c) = it.value();
    }
    const double norm = at.col(c).norm();
    if (norm > 0.0) at.col(c) /= norm;
  }
  const Eigen::VectorXd z = free_motion(at);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(jac.cols());
  for (std::size_t i = 0; i < dofs.size(); ++i) v[dofs[i]] = z[static_cast<Eigen::Index>(i)];
  return v;
}

}  // namespace

/// Along a motion the rows allow at t = 0, with velocity v, the dependent rows' second
/// derivatives combine as their gradients do exactly when the dependence persists (the rows
/// span the dropped one along the motion): sum_k w_k γ_k(u0, v) / |a_k| = 0. A singular start
/// (a pendulum driven along x from the horizontal) fails it for almost every v; v is v0 plus a
/// free motion of v0's size, so a rest start is tested too.
void ModelBuilder::check_redundant_at_second_order(const std::vector<std::pair<int, double>>& combo,
                                                   const std::vector<double>& row_norm,
                                                   const ConstraintGroup& group,
                                                   const std::string& names,
                                                   const std::string& rank_text) const {
  const SourcePoint& where =
      model_.constraints[static_cast<std::size_t>(combo.front().first)].where;
  const auto evaluator = model_.evaluator();
  MechanicalSystem& s = *evaluator;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> jac(s.constraint_jacobian(0.0, model_.u0));
  std::vector<int> group_rows, rows;
  for (const int j : group.rows) group_rows.push_back(system_row(j));
  for (int j = 0; j < model_.constraint_count(); ++j) rows.push_back(system_row(j));
  const auto z = free_velocity(jac, group_rows, rows);
  if (!z) {
    report_.warnings.push_back(
        "the constraints " + names + " are dependent at the initial configuration (" + rank_text +
        ") and one is dropped, but the rows around them are too many to test whether they stay "
        "dependent along the motion: if they are dependent at t = 0 only, the run loses the "
        "dropped one's constraint");
    return;
  }
  // z's sign taken along v0, so that the two never cancel (a one-DOF mechanism's free motion is
  // v0's own direction): |v| >= |z| times the speed.
  const double speed = std::max(1.0, model_.v0.lpNorm<Eigen::Infinity>());
  const Eigen::VectorXd v = model_.v0 + (model_.v0.dot(*z) < 0.0 ? -speed : speed) * (*z);
  Eigen::VectorXd gamma(s.constraints());
  s.acceleration_bias(0.0, model_.u0, v, gamma);
  double sum = 0.0, size = 0.0;
  for (const auto& [j, w] : combo) {
    const double term = w * gamma[system_row(j)] / row_norm[static_cast<std::size_t>(j)];
    sum += term;
    size += std::abs(term);
  }
  // Negated: a NaN is a failure, never a pass.
  if (!(std::abs(sum) <= kSecondOrderTolerance * size)) {
    fail(where,
         "the constraints " + names + " are linearly dependent at the initial configuration (" +
             rank_text +
             "), and [solve] redundant = \"drop\" asks to drop one, but they are not "
             "redundant: along a motion they allow there, their dependence fails at second "
             "order (their accelerations' right-hand sides combine to " +
             computed_fmt(sum, "the accelerations' right-hand sides") + " against terms of " +
             fmt(size) +
             "), so this is a singular configuration of the set, which may be independent "
             "everywhere else, and a dropped row would be lost there: start away from it "
             "(other [initial] displacements, or a prescribed motion that starts elsewhere)");
  }
}

void ModelBuilder::keep_independent_rows() {
  if (kept_rows_.empty()) return;
  if (model_.outputs) {  // a mechanism's map reads every row's multiplier
    model_.outputs = std::make_shared<RowSubsetOutputs>(model_.outputs, kept_rows_,
                                                        model_.system->constraints());
  }
  model_.system = std::make_shared<RowSubsetSystem>(*model_.system, kept_rows_);
  kept_rows_.clear();
}

}  // namespace condyn
