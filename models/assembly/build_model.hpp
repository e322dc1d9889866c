#pragma once
/// A validated scene to a constant Model (models/core/model.hpp): the builder's entry points.
/// The stages, in the order build_model() runs them, are models/assembly/build_model.cpp.

#include "models/core/model.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn {

/// Builds and checks the model: DOF names, geometry, matrix properties, constraint rank and
/// compatibility, initial consistency. Throws SceneError naming file, line and key. `report`
/// receives what the build found worth telling.
[[nodiscard]] Model build_model(const SceneSpec& spec, BuildReport& report);
/// The same, for callers that do not print the report.
[[nodiscard]] Model build_model(const SceneSpec& spec);
/// Frees what build_model copied into the Model (the model's description, loads, constraints,
/// ground motion and initial values; `file`, `name`, `solve`, `output` and `checks` stay), so that
/// a run holds the model once, not twice (docs/benchmarks.md). For callers done with building.
void release_model_input(SceneSpec& spec);

}  // namespace condyn
