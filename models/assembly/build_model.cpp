#include "models/assembly/model_builder.hpp"

namespace condyn {

// The stages, in the order they need each other (the stages themselves:
// models/assembly/model_builder.hpp):
//  1. The model type's own part (truss_assembly, matrix_model, nonlinear_systems) comes first: it
//     names the DOFs, in which every later stage looks names up; and a truss's gravity loads
//     enter the load list before the scene's, whose sum per DOF build_loads bounds; a built-in
//     benchmark also brings its system, constraints and published initial state here.
//     apply_rayleigh needs the type's M and K (1). A matrix model first checks, on what the
//     scene wrote, that something acts on every DOF (check_unreached_dofs), before the names'
//     index and the definiteness checks, which grow with the model.
//  2. build_loads needs the DOF names (1).
//  3. build_initial needs the DOF names and a benchmark's published state (1).
//  4. build_constraints (linear models; a nonlinear system brings its own rows) needs u(0) (3):
//     a velocity row's position_value integrates from a·u(0).
//  5. finish_point_masses / finish_sleigh build the nonlinear system, which takes the loads (2)
//     and, for a truss, the linear rows (4), its rod rows after them.
//  6. check_size estimates memory from the final counts and nonzeros (1, 4, 5), and comes before
//     the work that grows with the model (projection, rank check), so a model that cannot fit is
//     refused before it exhausts memory.
//  7. project_initial needs the system (M, C, K, A of a linear model, or 5) and the constraints;
//     it rebuilds a linear model's rows (4) from the projected u(0).
//  8. A benchmark keeps its reference only when the final initial state (3, 7) is the published
//     one.
//  9. linearize gives a nonlinear model its M, C, K, A at the final (u0, v0) (7).
// 10. check_finite, check_magnitudes and check_degenerate_dofs read all four matrices (1, 4, 9)
//     and the initial state; the rank check factors A, so it must be finite first.
// 11. The rank check drops redundant rows (or refuses dependent ones) before the checks that go
//     through the rows one by one or count them: initial consistency, the mass matrix on the
//     motions A allows, and [solve] slaves (one per remaining constraint). A nonlinear model's
//     system is restricted to the kept rows once they are final (keep_independent_rows), and a
//     mechanism's joints are reported with the rows they keep and those dropped (report_joints).
// 12. solve_static_initial ([initial] static = true) factors [K Aᵀ; A 0]: after the rank check
//     (11), whose dropped rows would make it singular; check_initial_consistency then tests the
//     final state (7 or 12) against the remaining rows (11).
// 13. The mass checks need M (1, 9) and the final A (11).
// 14. check_energy_output evaluates the final system at (u0, v0); check_output's slave check
//     needs the final A and the dropped rows (11).
// 15. build_derived resolves [[derived]] terms against the final columns: the DOFs or the
//     mechanism's output map (1), the constraints left after drops (11).
Model ModelBuilder::build() {
  model_.file = spec_.file;
  model_.name = spec_.name;
  switch (spec_.model.type) {
    case ModelSpec::Type::truss2d:
    case ModelSpec::Type::truss3d:
      build_truss();
      break;
    case ModelSpec::Type::matrix:
      build_matrix();
      break;
    case ModelSpec::Type::sleigh:
      build_sleigh();
      break;
    case ModelSpec::Type::andrews:
    case ModelSpec::Type::car_axis:
    case ModelSpec::Type::pendulum:
      build_benchmark();
      break;
    case ModelSpec::Type::multibody:
      build_mechanism();
      break;
  }
  apply_rayleigh();
  build_loads();
  build_initial();
  if (!model_.is_nonlinear()) build_constraints();
  if (nonlinear_truss_) finish_point_masses();
  if (spec_.model.type == ModelSpec::Type::sleigh) finish_sleigh();
  check_size();
  if (spec_.initial.project && spec_.model.mechanism) {
    project_mechanism();
  } else if (spec_.initial.project) {
    project_initial();
  }
  keep_reference_only_at_published_start();
  if (model_.is_nonlinear()) linearize();
  check_finite();
  check_magnitudes();
  check_tolerance();
  check_degenerate_dofs();
  while (const auto dependent = check_rank()) drop_constraint(*dependent);
  keep_independent_rows();
  if (spec_.model.mechanism) report_joints();  // its rows as kept (after the drops)
  apply_modal_damping();   // from the modes of the constrained model: after the rows are final
  apply_rayleigh_modes();  // likewise
  if (spec_.initial.static_start) solve_static_initial();
  check_initial_consistency();
  if (!model_.is_nonlinear()) settle_initial_roundoff();
  check_massless_dofs();
  check_energy_output();
  check_output();
  build_derived();
  // Last: the linear system copies the model's final matrices, constraints and loads.
  if (!model_.nonlinear) model_.system = std::make_shared<LinearSystem>(model_);
  return std::move(model_);
}

Model build_model(const SceneSpec& spec, BuildReport& report) {
  report = {};
  return ModelBuilder(spec, report).build();
}

Model build_model(const SceneSpec& spec) {
  BuildReport ignored;
  return build_model(spec, ignored);
}

void release_model_input(SceneSpec& spec) {
  // Eigen 3.4's SparseMatrix has no move assignment: assigning an empty one keeps the storage
  // (a resize), so the file matrices are swapped out first (FileMatrix::release); a test checks
  // the storage is freed (docs/benchmarks.md).
  for (FileMatrix* m :
       {&spec.model.mass_file, &spec.model.stiffness_file, &spec.model.damping_file})
    m->release();
  spec.model = ModelSpec{};
  std::vector<LoadSpec>().swap(spec.loads);
  std::vector<ConstraintSpec>().swap(spec.constraints);
  std::vector<ConstraintBlockSpec>().swap(spec.constraint_blocks);
  spec.ground_motion.reset();
  spec.initial = InitialSpec{};
}

}  // namespace condyn
