// Nonlinear systems: which MechanicalSystem a scene gets (built-in benchmarks, the sleigh,
// point masses for rigid members or large displacements), and its linearization at t = 0.

#include <memory>

#include "models/assembly/model_builder.hpp"
#include "models/systems/benchmarks.hpp"
#include "models/systems/point_mass_system.hpp"
#include "models/systems/sleigh.hpp"

namespace condyn {

/// The built-in benchmark models: every parameter fixed by the published problem.
void ModelBuilder::build_benchmark() {
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

void ModelBuilder::build_sleigh() {
  set_dofs({"x", "y", "theta"});
  if (!spec_.constraints.empty()) {
    fail(spec_.constraints.front().where,
         "the sleigh brings its own knife-edge constraint: remove the [[constraint]] entries");
  }
  model_.description =
      "Chaplygin sleigh: a rigid body on a knife edge at distance contact_offset ahead of its "
      "centre of mass";
}

void ModelBuilder::finish_sleigh() {
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
void ModelBuilder::finish_point_masses() {
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

/// A published reference belongs to the published initial state: a scene that starts the
/// benchmark elsewhere is still a valid model, but no longer that benchmark.
void ModelBuilder::keep_reference_only_at_published_start() {
  if (model_.reference && (model_.u0 != base_u0_ || model_.v0 != base_v0_)) {
    model_.reference = nullptr;
    model_.description +=
        " (started from the scene's [initial], not the published state: "
        "no reference)";
  }
}

/// M, C, K, A of a nonlinear model: its linearization at t = 0, (u0, v0).
void ModelBuilder::linearize() {
  const auto evaluator = model_.evaluator();
  MechanicalSystem& s = *evaluator;
  model_.M = s.mass(0.0, model_.u0);
  model_.K.edit() = s.stiffness(0.0, model_.u0, model_.v0);
  model_.C = s.damping(0.0, model_.u0, model_.v0);
  if (model_.C.rows() != model_.dofs()) model_.C.resize(model_.dofs(), model_.dofs());
  model_.A = s.constraint_jacobian(0.0, model_.u0);
  for (auto* mat : {&model_.M, &model_.K.edit(), &model_.C, &model_.A}) mat->prune(0.0);
}

}  // namespace condyn
