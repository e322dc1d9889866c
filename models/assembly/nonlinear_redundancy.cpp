// [solve] redundant = "drop" on a nonlinear model: whether rows dependent at t = 0 are redundant
// or only singular there, and the system restricted to the rows kept.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>

#include "models/assembly/model_builder.hpp"
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

}  // namespace

/// Along a motion the rows allow at t = 0, with velocity v, the dependent rows' second
/// derivatives combine as their gradients do exactly when the dependence persists (the rows
/// span the dropped one along the motion): sum_k w_k γ_k(u0, v) / |a_k| = 0. A singular start
/// (a pendulum driven along x from the horizontal) fails it for almost every v; v is v0 plus a
/// free motion of v0's size, so a rest start is tested too.
void ModelBuilder::check_redundant_at_second_order(
    const std::vector<std::pair<int, double>>& combo, const std::vector<double>& row_norm,
    const ConstraintGroup& group, const std::string& names, const std::string& rank_text) const {
  const SourcePoint& where = model_.constraints[static_cast<std::size_t>(combo.front().first)].where;
  const auto mc = static_cast<Eigen::Index>(group.rows.size());
  const auto nc = static_cast<Eigen::Index>(group.dofs.size());
  if (static_cast<double>(mc) * static_cast<double>(nc) > kMaxDenseEntries) {
    report_.warnings.push_back(
        "the constraints " + names + " are dependent at the initial configuration (" + rank_text +
        ") and one is dropped, but their group is too large (" + std::to_string(mc) + " rows on " +
        std::to_string(nc) +
        " DOFs) to test whether they stay dependent along the motion: if they are dependent at "
        "t = 0 only, the run loses the dropped one's constraint");
    return;
  }
  std::vector<int> local(static_cast<std::size_t>(model_.dofs()), -1);
  for (Eigen::Index i = 0; i < nc; ++i) local[static_cast<std::size_t>(group.dofs[i])] = static_cast<int>(i);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> a(model_.A);
  Eigen::MatrixXd at = Eigen::MatrixXd::Zero(nc, mc);
  for (Eigen::Index c = 0; c < mc; ++c) {
    const int j = group.rows[static_cast<std::size_t>(c)];
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, j); it; ++it) {
      at(local[static_cast<std::size_t>(it.col())], c) =
          it.value() / row_norm[static_cast<std::size_t>(j)];
    }
  }
  const Eigen::VectorXd z = free_motion(at);
  const double speed = std::max(1.0, model_.v0.lpNorm<Eigen::Infinity>());
  Eigen::VectorXd v = model_.v0;
  for (Eigen::Index i = 0; i < nc; ++i) v[group.dofs[static_cast<std::size_t>(i)]] += speed * z[i];
  const auto evaluator = model_.evaluator();
  Eigen::VectorXd gamma(evaluator->constraints());
  evaluator->acceleration_bias(0.0, model_.u0, v, gamma);
  double sum = 0.0, size = 0.0;
  for (const auto& [j, w] : combo) {
    const double term = w * gamma[system_row(j)] / row_norm[static_cast<std::size_t>(j)];
    sum += term;
    size += std::abs(term);
  }
  // Negated: a NaN is a failure, never a pass.
  if (!(std::abs(sum) <= kSecondOrderTolerance * size)) {
    fail(where, "the constraints " + names + " are linearly dependent at the initial configuration (" +
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
  model_.system = std::make_shared<RowSubsetSystem>(*model_.system, kept_rows_);
  kept_rows_.clear();
}

}  // namespace condyn
