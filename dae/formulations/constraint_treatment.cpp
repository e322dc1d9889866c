// The treatment per constraint row (dae/formulations/constraint_treatment.hpp).

#include "dae/formulations/constraint_treatment.hpp"

#include <algorithm>
#include <array>
#include <sstream>

#include "models/core/constraint_groups.hpp"

namespace condyn {

namespace {

using Reason = ConstraintTreatment::Reason;
using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// The transform of a group is built here only to learn whether it stays sparse, and its dense
/// work grows like rows² × DOFs (the column-pivoted QR that picks the slaves, the LU, its solves
/// and the condition number): a fraction of a second at this many. Within the dense block's
/// limits (kMaxDenseGroupEntries) a group can cost seconds more, many times the run it serves:
/// the joint rows of a chain of 1,000 bodies form such groups, in natural coordinates (figures in
/// docs/benchmarks.md, "Chains of rigid bodies"). A larger group keeps its multipliers without
/// the trial; realistic linear groups (supports, ties, rigid links) are far smaller, and
/// `scheme = "elimination"` still eliminates a larger one.
constexpr double kMaxTrialWork = 1e8;

bool within_trial_work(std::size_t rows, std::size_t dofs) {
  const double r = static_cast<double>(rows);
  return r * r * static_cast<double>(dofs) <= kMaxTrialWork;
}

/// The rows' coefficients as a matrix (rows in the given order).
RowMajor rows_of(const Model& model, const std::vector<int>& rows) {
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    for (const auto& [dof, a] : model.constraints[static_cast<std::size_t>(rows[k])].coefficients)
      trip.emplace_back(static_cast<int>(k), dof, a);
  }
  RowMajor a(static_cast<Eigen::Index>(rows.size()), model.dofs());
  a.setFromTriplets(trip.begin(), trip.end());
  return a;
}

/// deg(s): the nonzeros of column s of M, C or K, the largest (each is symmetric).
std::vector<long> degrees(const Model& model) {
  std::vector<long> deg(static_cast<std::size_t>(model.dofs()), 0);
  for (const auto* mat : {&model.M, &model.C, &*model.K}) {
    if (mat->cols() != model.dofs()) continue;
    for (Eigen::Index j = 0; j < mat->outerSize(); ++j) {
      long count = 0;
      for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, j); it; ++it) ++count;
      auto& d = deg[static_cast<std::size_t>(j)];
      d = std::max(d, count);
    }
  }
  return deg;
}

}  // namespace

bool is_eliminated(Reason r) { return r == Reason::single_freedom || r == Reason::sparse_group; }

std::string describe(Reason r) {
  switch (r) {
    case Reason::single_freedom:
      return "eliminated (single-freedom: removes the DOF)";
    case Reason::sparse_group:
      return "eliminated by master-slave (the transform stays sparse)";
    case Reason::fills_in:
      return "multipliers (master-slave would fill in)";
    case Reason::group_too_large:
      return "multipliers (coupled group too large for the dense transform)";
    case Reason::nonlinear:
      return "multipliers (nonlinear)";
    case Reason::nonholonomic:
      return "multipliers (nonholonomic)";
  }
  return "";
}

ConstraintTreatment treat_constraints(const Model& model) {
  const int m = model.constraint_count();
  ConstraintTreatment out;
  out.reason.assign(static_cast<std::size_t>(m), Reason::nonlinear);
  out.fill.assign(static_cast<std::size_t>(m), 0);
  out.group_nonzeros.assign(static_cast<std::size_t>(m), 0);
  std::vector<int> candidates;
  for (int i = 0; i < m; ++i) {
    const Constraint& c = model.constraints[static_cast<std::size_t>(i)];
    if (c.nonholonomic) {
      out.reason[static_cast<std::size_t>(i)] = Reason::nonholonomic;
    } else if (!c.coefficients.empty()) {
      candidates.push_back(i);  // linear, constant coefficients, integrable
    }
  }
  const RowMajor a = rows_of(model, candidates);
  const std::vector<ConstraintGroup> groups = constraint_groups(a);
  // First pass: every candidate group within the dense block limit is eliminated; then the
  // groups whose transform fills in are handed back to multipliers.
  std::vector<bool> eliminate(candidates.size(), false);
  for (const auto& g : groups) {
    const bool within = group_within_dense_limits(g.rows.size(), g.dofs.size()) &&
                        within_trial_work(g.rows.size(), g.dofs.size());
    const bool single = g.rows.size() == 1 && g.dofs.size() == 1;
    for (int r : g.rows) {
      const auto row = static_cast<std::size_t>(candidates[static_cast<std::size_t>(r)]);
      out.reason[row] = !within  ? Reason::group_too_large
                        : single ? Reason::single_freedom
                                 : Reason::sparse_group;
      eliminate[static_cast<std::size_t>(r)] = within;
    }
  }
  const auto selected = [&] {
    std::vector<int> rows;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (eliminate[k]) rows.push_back(candidates[k]);
    }
    return rows;
  };
  std::vector<int> global = selected();
  out.transform = master_slave_transform(rows_of(model, global));
  const bool any_group = std::any_of(out.reason.begin(), out.reason.end(),
                                     [](Reason r) { return r == Reason::sparse_group; });
  if (any_group) {
    // |T_s|: the masters slave s is replaced by (the nonzeros of its row of T).
    const auto& T = out.transform.T;
    std::vector<long> masters_of(static_cast<std::size_t>(model.dofs()), 0);
    for (Eigen::Index j = 0; j < T.outerSize(); ++j) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(T, j); it; ++it)
        ++masters_of[static_cast<std::size_t>(it.row())];
    }
    std::vector<bool> is_slave(static_cast<std::size_t>(model.dofs()), false);
    for (int s : out.transform.slaves) is_slave[static_cast<std::size_t>(s)] = true;
    const std::vector<long> deg = degrees(model);
    bool dropped = false;
    for (const auto& g : groups) {
      const auto first = static_cast<std::size_t>(candidates[static_cast<std::size_t>(g.rows[0])]);
      if (out.reason[first] != Reason::sparse_group) continue;
      long fill = 0, nonzeros = 0;
      for (int d : g.dofs) {
        const auto s = static_cast<std::size_t>(d);
        if (is_slave[s]) fill += deg[s] * std::max(masters_of[s] - 1, 0L);
      }
      for (int r : g.rows) nonzeros += a.row(r).nonZeros();
      const bool fills_in = fill > nonzeros;
      dropped = dropped || fills_in;
      for (int r : g.rows) {
        const auto row = static_cast<std::size_t>(candidates[static_cast<std::size_t>(r)]);
        out.fill[row] = fill;
        out.group_nonzeros[row] = nonzeros;
        if (fills_in) {
          out.reason[row] = Reason::fills_in;
          eliminate[static_cast<std::size_t>(r)] = false;
        }
      }
    }
    if (dropped) {
      global = selected();
      out.transform = master_slave_transform(rows_of(model, global));
    }
  }
  out.eliminated = global;
  for (int i = 0; i < m; ++i) {
    if (!is_eliminated(out.reason[static_cast<std::size_t>(i)])) out.kept.push_back(i);
  }
  return out;
}

std::string treatment_report(const Model& model, const ConstraintTreatment& t, std::size_t limit) {
  constexpr std::array kReasons = {Reason::single_freedom, Reason::sparse_group,
                                   Reason::fills_in,       Reason::group_too_large,
                                   Reason::nonlinear,      Reason::nonholonomic};
  std::ostringstream out;
  out << t.eliminated.size() << " eliminated, " << t.kept.size() << " with multipliers\n";
  for (Reason r : kReasons) {
    const auto count = std::count(t.reason.begin(), t.reason.end(), r);
    if (count > 0) out << "  " << count << " " << describe(r) << "\n";
  }
  std::size_t named = 0;
  for (int row : t.kept) {
    if (named == limit) {
      out << "  ... and " << t.kept.size() - limit << " more with multipliers\n";
      break;
    }
    const auto i = static_cast<std::size_t>(row);
    out << "  " << model.constraints[i].name << ": " << describe(t.reason[i]);
    if (t.reason[i] == Reason::fills_in) {
      out << ", about " << t.fill[i] << " nonzeros added against " << t.group_nonzeros[i]
          << " in its rows";
    }
    out << "\n";
    ++named;
  }
  return out.str();
}

}  // namespace condyn
