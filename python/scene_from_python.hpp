#pragma once
/// A Python scene (a path, or a dict with the TOML's structure) → SceneSpec, through the same
/// parser as a file (models/scene/scene_table.hpp). Needs the GIL.

#include <pybind11/pybind11.h>

#include <string>

#include "models/scene/scene_needs.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn::python {

/// The name a dict scene has in messages ("<dict>: model.mass: ...").
inline constexpr const char* kDictFile = "<dict>";

/// Parses `scene`: a str or os.PathLike names a scene file; a dict is converted key by key
/// (numbers, strings, booleans, lists, dicts; numpy arrays and scipy.sparse matrices where the
/// scene takes a matrix: model.mass, model.stiffness, model.damping, load.pattern,
/// constraint_block.file and constraint_block.value), refused first if it lacks what `needs` asks
/// for. Throws SceneError.
[[nodiscard]] SceneSpec parse_python_scene(const pybind11::handle& scene, SceneNeeds needs = {});

/// Text the program wrote (a message, a file name) as a Python str: UTF-8, with bytes that are
/// not (a file name as the system gave it) as Python's surrogateescape, the str os.fsencode
/// turns back into the same bytes.
[[nodiscard]] pybind11::str system_text(const std::string& text);

}  // namespace condyn::python
