// [[constraint_block]]: the rows of a Matrix Market matrix A (m x n) as m position-level
// constraints A u = scale(t) g, named PREFIX1..PREFIXm, appended after the scene's [[constraint]]s.
// Linear in the nonzeros: one pass over A stored by rows.

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/assembly/model_builder.hpp"

namespace condyn {

void ModelBuilder::append_constraint_blocks(std::vector<Eigen::Triplet<double>>& trip) {
  const int n = model_.dofs();
  for (const auto& b : spec_.constraint_blocks) {
    const SourcePoint file_at = b.A.where;
    if (b.A.matrix.cols() != n) {
      fail(file_at, b.A.file + " is " + std::to_string(b.A.matrix.rows()) + " x " +
                        std::to_string(b.A.matrix.cols()) +
                        ": a constraint block needs one column "
                        "per DOF (" +
                        std::to_string(n) + ")");
    }
    const SourcePoint scale_at{b.where.path + ".scale", b.where.line};
    refuse_table_rhs(b.scale, scale_at, false);
    check_time_function(b.scale, scale_at, true);
    const TimeFunction scale = acting_in_run(b.scale, scale_at);
    for (double t : scale.breakpoints()) {
      fail(scale_at, "a step at t = " + fmt(t) +
                         " > 0 would make the prescribed displacements jump (an infinite "
                         "velocity); use a smooth function or a step at t = 0");
    }
    const double scale_bound = magnitude_bound(scale, spec_.solve.t_end);
    const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = b.A.matrix;
    Eigen::VectorXd g = Eigen::VectorXd::Zero(rows.rows());
    if (b.g.given()) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(b.g.matrix, 0); it; ++it) {
        g[it.row()] = it.value();
      }
    }
    for (Eigen::Index i = 0; i < rows.outerSize(); ++i) {
      Constraint c;
      c.name = b.prefix + std::to_string(i + 1);
      c.level = ConstraintSpec::Level::position;
      c.where = b.where;
      double largest = 0.0;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, i); it; ++it) {
        largest = std::max(largest, std::abs(it.value()));
      }
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, i); it; ++it) {
        const double a = std::abs(it.value());
        if (a == 0.0) continue;
        // The [[constraint]] rule (constraint_rows.cpp): a term must carry information.
        if (a < std::numeric_limits<double>::min() ||
            a < std::numeric_limits<double>::epsilon() * largest) {
          fail(file_at, b.A.file + ": row " + std::to_string(i + 1) + ", column " +
                            std::to_string(it.col() + 1) + ": the coefficient " + fmt(it.value()) +
                            " is subnormal or below the roundoff of the row's largest (" +
                            fmt(largest) + "); remove it or rescale the row");
        }
        c.coefficients.emplace_back(static_cast<int>(it.col()), it.value());
      }
      if (c.coefficients.empty()) {
        fail(file_at, b.A.file + ": row " + std::to_string(i + 1) +
                          " has no nonzero entry: constraint '" + c.name + "' constrains nothing");
      }
      if (!std::isfinite(scale_bound * std::abs(g[i]))) {
        fail(scale_at, "times the right-hand side " + fmt(g[i]) + " of row " +
                           std::to_string(i + 1) + " overflows the double range");
      }
      c.value = scale.scaled(g[i]);
      c.position_value = c.value;
      const int row = static_cast<int>(model_.constraints.size());
      for (const auto& [d, a] : c.coefficients) trip.emplace_back(row, d, a);
      model_.constraints.push_back(std::move(c));
    }
  }
}

}  // namespace condyn
