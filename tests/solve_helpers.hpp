#pragma once
// Running a scene in tests: the model is built from the spec and run under the spec's settings,
// with the scheme of the case.

#include <string>
#include <utility>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"

namespace condyn::test {

/// A scene's settings, the model built from it and what the build reported.
struct BuiltScene {
  SceneSpec spec;
  Model model;
  BuildReport report;
};

/// A scene condyn ships (`path` below models/scenes/), read as a user's file is.
inline SceneSpec shipped_scene(const std::string& path) {
  return parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/" + path);
}

inline BuiltScene built(SceneSpec spec) {
  BuildReport report;
  Model model = build_model(spec, report);
  return {std::move(spec), std::move(model), std::move(report)};
}

/// `settings` with another scheme.
inline SolveSpec under(SolveSpec settings, Scheme scheme) {
  settings.scheme = scheme;
  return settings;
}

/// solve() for a run the test expects to succeed: a failed run throws its message (the test case
/// fails with it, as an uncaught exception).
inline SolveResult solved(const Model& model, const SolveSpec& settings,
                          const RunHooks& hooks = {}) {
  SolveResult result = solve(model, settings, hooks);
  (void)succeeded(result);
  return result;
}

}  // namespace condyn::test
