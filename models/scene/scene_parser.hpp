#pragma once
/// Scene file → SceneSpec. Every key is checked: unknown keys, wrong types, non-finite numbers and
/// out-of-range values are errors that name the file, the line and the key path.

#include <string>

#include "models/core/source_point.hpp"
#include "models/scene/scene_needs.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn {

/// "FILE: has no [[check]] table: nothing to check".
[[nodiscard]] std::string no_checks_message(const std::string& file);

/// Reads and validates a scene file. Throws SceneError.
[[nodiscard]] SceneSpec parse_scene_file(const std::string& path, SceneNeeds needs = {});
/// Same for scene text already in memory; `file` names it in messages.
[[nodiscard]] SceneSpec parse_scene_text(const std::string& text, const std::string& file,
                                         SceneNeeds needs = {});

}  // namespace condyn
