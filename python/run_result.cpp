#include "python/run_result.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "dae/run/mapped_rows.hpp"
#include "dae/run/singular_passages.hpp"
#include "dae/run/solve.hpp"

namespace py = pybind11;

namespace condyn::python {

namespace {

/// An nt x cols view of a cols x nt column-major matrix held by `owner` (read-only).
py::object rows_view(const Eigen::MatrixXd& m, Eigen::Index nt, Eigen::Index cols,
                     const py::object& owner) {
  if (nt == 0 || cols == 0) {
    return py::array_t<double>({static_cast<py::ssize_t>(nt), static_cast<py::ssize_t>(cols)});
  }
  if (m.cols() != nt || m.rows() != cols) {
    throw std::logic_error("condyn: a result matrix is " + std::to_string(m.rows()) + " x " +
                           std::to_string(m.cols()) + ", expected " + std::to_string(cols) + " x " +
                           std::to_string(nt));
  }
  const auto s = static_cast<py::ssize_t>(sizeof(double));
  py::array_t<double> a({static_cast<py::ssize_t>(nt), static_cast<py::ssize_t>(cols)},
                        {static_cast<py::ssize_t>(cols) * s, s}, m.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// A read-only view of `size` doubles at `data`, held by `owner`.
py::array_t<double> read_only_view(const double* data, Eigen::Index size, const py::object& owner) {
  if (size == 0) return py::array_t<double>(0);
  py::array_t<double> a({static_cast<py::ssize_t>(size)}, {sizeof(double)}, data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// A read-only view of `x` held by `owner`, or None when it is empty.
py::object vector_view(const Eigen::VectorXd& x, const py::object& owner) {
  if (x.size() == 0) return py::none();
  return read_only_view(x.data(), x.size(), owner);
}

/// The run's passages near a singular configuration (dae/interface/singular_passage.hpp), one dict
/// each.
py::list passage_list(const std::vector<SingularPassage>& passages) {
  py::list out;
  for (const SingularPassage& p : passages) {
    py::dict d;
    d["t_enter"] = p.t_enter;
    d["t_closest"] = p.t_closest;
    d["t_leave"] = p.left_open ? py::object(py::none()) : py::float_(p.t_leave);
    d["closest"] = p.closest;
    d["branch_change"] =
        p.branch_change < 0.0 ? py::object(py::none()) : py::float_(p.branch_change);
    d["left_branch"] = p.left_branch();
    out.append(d);
  }
  return out;
}

/// The [[derived]] columns at every row (nt x k; k = 0 without any), from the trajectory's
/// vectors (a mechanism's in its output map's columns).
py::array_t<double> derived_rows(const Model& model, const Trajectory& traj) {
  const auto nt = static_cast<py::ssize_t>(traj.t.size());
  const auto k = static_cast<py::ssize_t>(model.derived.size());
  py::array_t<double> out({nt, k});
  auto w = out.mutable_unchecked<2>();
  const Eigen::VectorXd none;
  for (py::ssize_t i = 0; i < nt; ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    const Eigen::Ref<const Eigen::VectorXd> a =
        traj.acceleration.cols() > r ? Eigen::Ref<const Eigen::VectorXd>(traj.acceleration.col(r))
                                     : Eigen::Ref<const Eigen::VectorXd>(none);
    const Eigen::VectorXd values = model.derived_values(
        traj.t[static_cast<std::size_t>(i)], traj.u.col(r), traj.v.col(r), a, traj.reaction.col(r));
    for (py::ssize_t c = 0; c < k; ++c) w(i, c) = values[static_cast<Eigen::Index>(c)];
  }
  return out;
}

py::dict summary_dict(const SolveSummary& s, const SolveSpec& settings, const BuildReport& r,
                      const char* treatment) {
  py::dict d;
  d["scheme"] = s.scheme;
  d["constraints"] = treatment != nullptr ? py::object(py::str(treatment)) : py::none();
  d["steps"] = s.steps;
  d["wall_s"] = s.wall_seconds;
  d["rtol"] = settings.rtol;
  d["atol"] = settings.atol;
  d["residual_evals"] = s.residual_evals;
  d["jacobian_evals"] = s.jacobian_evals;
  d["newton_iterations"] = s.newton_iterations;
  d["newton_failures"] = s.newton_failures;
  d["error_test_failures"] = s.error_test_failures;
  d["restarts"] = s.restarts;
  d["max_order_used"] = s.max_order_used;
  d["last_step"] = s.last_step;
  d["max_drift_position"] = s.max_drift_position;
  d["max_drift_velocity"] = s.max_drift_velocity;
  d["worst_drift_joint"] =
      s.worst_drift_joint.empty() ? py::object(py::none()) : py::str(s.worst_drift_joint);
  d["worst_drift_body"] =
      s.worst_drift_body.empty() ? py::object(py::none()) : py::str(s.worst_drift_body);
  d["max_abs_mu"] = s.max_abs_mu < 0.0 ? py::object(py::none()) : py::float_(s.max_abs_mu);
  d["unknowns"] = s.unknowns;
  d["jacobian_nonzeros"] = s.jacobian_nonzeros;
  d["termination"] = s.termination;
  d["notes"] = s.notes_text();
  d["brief"] = s.brief();
  std::vector<std::string> warnings = r.warnings;
  for (auto& w : singular_passage_warnings(s.singular_passages)) warnings.push_back(std::move(w));
  d["warnings"] = warnings;
  d["singular_passages"] = passage_list(s.singular_passages);
  d["initial_state"] = r.initial_projection;
  d["damping"] = r.damping;
  d["dropped_constraints"] = r.dropped_constraints;
  return d;
}

}  // namespace

py::dict result_dict(SolveResult&& result, const Model& model, const SolveSpec& settings,
                     const BuildReport& report, const OutputSpec& output) {
  const OutputMap* map = model.outputs.get();
  const std::vector<int> points =
      map != nullptr ? point_indices(*map, output.points) : std::vector<int>();
  const auto& asked = output.quantities;
  const bool absolute_acceleration =
      std::find(asked.begin(), asked.end(), Quantity::absolute_acceleration) != asked.end();
  // The trajectory (a mechanism's in its output map's columns, every row's reaction included:
  // the module always asks for them) moves into a capsule that every array keeps alive.
  auto* held = new Trajectory(mapped_trajectory(model, std::move(result.trajectory), points, true));
  const py::capsule owner(held, [](void* p) { delete static_cast<Trajectory*>(p); });
  const Trajectory& traj = *held;
  const auto nt = static_cast<Eigen::Index>(traj.t.size());
  const auto width = [&](Quantity q) {
    return static_cast<Eigen::Index>(map != nullptr ? map->names(q).size()
                                                    : model.dof_names.size());
  };
  const auto n = width(Quantity::displacement);
  const auto m = static_cast<Eigen::Index>(model.constraint_count());

  py::dict d;
  d["t"] = read_only_view(traj.t.data(), nt, owner);
  d["u"] = rows_view(traj.u, nt, n, owner);
  d["v"] = rows_view(traj.v, nt, width(Quantity::velocity), owner);
  d["reaction"] = rows_view(traj.reaction, nt, width(Quantity::reaction), owner);
  d["multiplier"] = rows_view(traj.multiplier, nt, m, owner);
  py::array_t<double> drift({static_cast<py::ssize_t>(nt), py::ssize_t{2}});
  auto w = drift.mutable_unchecked<2>();
  if (traj.drift_position.size() != nt || traj.drift_velocity.size() != nt) {
    throw std::logic_error("condyn: the drift has " + std::to_string(traj.drift_position.size()) +
                           " rows for " + std::to_string(nt) + " output times");
  }
  for (Eigen::Index i = 0; i < nt; ++i) {
    w(i, 0) = traj.drift_position(i);
    w(i, 1) = traj.drift_velocity(i);
  }
  d["drift"] = drift;
  d["a"] = traj.acceleration.size() == 0
               ? py::object(py::none())
               : rows_view(traj.acceleration, nt, width(Quantity::acceleration), owner);
  d["a_abs"] = py::none();
  if (absolute_acceleration && traj.acceleration.size() > 0) {
    py::array_t<double> a_abs({static_cast<py::ssize_t>(nt), static_cast<py::ssize_t>(n)});
    auto out = a_abs.mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < nt; ++i) {
      const Eigen::VectorXd row = model.absolute_acceleration(traj.t[static_cast<std::size_t>(i)],
                                                              traj.acceleration.col(i));
      for (Eigen::Index j = 0; j < n; ++j) out(i, j) = row(j);
    }
    d["a_abs"] = a_abs;
  }
  if (traj.balance.empty()) {
    d["energy_balance"] = py::none();
  } else {
    const auto cols = static_cast<py::ssize_t>(kEnergyColumns.size());
    py::array_t<double> balance({static_cast<py::ssize_t>(traj.balance.size()), cols});
    auto b = balance.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < b.shape(0); ++i) {
      for (py::ssize_t c = 0; c < cols; ++c) {
        b(i, c) =
            energy_column(traj.balance[static_cast<std::size_t>(i)], static_cast<std::size_t>(c));
      }
    }
    d["energy_balance"] = balance;
  }
  d["derived"] = derived_rows(model, traj);
  std::vector<std::string> derived_names;
  for (const auto& column : model.derived) derived_names.push_back(column.name);
  d["derived_names"] = derived_names;
  const std::vector<bool> near = near_singular_rows(result.summary.singular_passages, traj.t);
  py::array_t<bool> near_singular(static_cast<py::ssize_t>(nt));
  for (Eigen::Index i = 0; i < nt; ++i)
    near_singular.mutable_at(i) = near[static_cast<std::size_t>(i)];
  d["near_singular"] = near_singular;
  d["energy_columns"] = energy_column_names();
  d["energy"] = vector_view(traj.energy, owner);
  d["kinetic"] = vector_view(traj.kinetic, owner);
  d["points"] = points.empty() ? py::object(py::none())
                               : rows_view(traj.points, nt, traj.points.rows(), owner);
  d["point_names"] =
      map != nullptr ? point_columns(*map, output.points) : std::vector<std::string>();
  // Every column: [output] dofs selects the files' columns, not the result's.
  const auto all_names = [&](Quantity q) {
    return map != nullptr ? map->names(q) : model.dof_names;
  };
  d["dof_names"] = all_names(Quantity::displacement);
  d["velocity_names"] = all_names(Quantity::velocity);
  d["acceleration_names"] = all_names(Quantity::acceleration);
  d["reaction_names"] = all_names(Quantity::reaction);
  std::vector<std::string> constraints;
  constraints.reserve(model.constraints.size());
  for (const auto& c : model.constraints) constraints.push_back(c.name);
  d["constraint_names"] = constraints;
  d["summary"] = summary_dict(result.summary, settings, report,
                              treatment_name(model, result.scheme, settings));
  return d;
}

}  // namespace condyn::python
