#pragma once
/// A scene's natural modes, as `condyn modes` and condyn.modes give them: the model built from the
/// scene, its constrained modes (dae/formulations/natural_modes.hpp), and every refusal turned into
/// a SceneError that names the scene and the key or argument at fault (exit 2 on the command line,
/// condyn.SceneError in Python).

#include <optional>
#include <string>
#include <vector>

#include "dae/formulations/natural_modes.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn {

struct SceneModes {
  std::string file;
  std::vector<std::string> dof_names;
  NaturalModes modes;
  bool ground_motion = false;  ///< the scene has [ground_motion]: mass ratios are given
};

/// The `count` lowest modes of the scene's model (default: kDefaultModeCount or all it has).
/// `count_key` names the count in messages (`--count`, `count`).
[[nodiscard]] SceneModes scene_modes(const SceneSpec& spec, std::optional<int> count,
                                     const std::string& count_key);

}  // namespace condyn
