#pragma once
/// The nodes a scene's DOFs move, for drawing deformed and mode shapes (`condyn plot --scene`,
/// docs/plots.md): a truss's nodes (DOFs ux<k>, uy<k>, uz<k>) and members as edges, a matrix
/// model's `[model] coordinates`; empty for a matrix model without them and for other models.

#include "models/core/node_map.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn {

[[nodiscard]] NodeMap scene_node_map(const SceneSpec& spec);

}  // namespace condyn
