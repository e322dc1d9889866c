// A scene's natural modes with its refusals named (scene_modes.hpp).

#include "validation/studies/scene_modes.hpp"

#include "models/assembly/build_model.hpp"

namespace condyn {

namespace {

/// The key where a scene gives its masses, for "no mass" refusals.
std::string mass_key(const ModelSpec& model) {
  switch (model.type) {
    case ModelSpec::Type::truss2d:
    case ModelSpec::Type::truss3d:
      return "model.masses";
    case ModelSpec::Type::matrix:
      return "model.mass";
    default:
      return "model";
  }
}

}  // namespace

SceneModes scene_modes(const SceneSpec& spec, std::optional<int> count,
                       const std::string& count_key) {
  SceneModes out;
  out.file = spec.file;
  const auto refuse = [&](const std::string& key, const std::string& problem) {
    throw SceneError(scene_message(spec.file, SourcePoint{key, 0}, problem));
  };
  const Model model = build_model(spec);
  out.dof_names = model.dof_names;
  out.ground_motion = model.ground.has_value();
  try {
    out.modes = natural_modes(model, count);
  } catch (const ModeCountError& e) {
    refuse(count_key, e.what());
  } catch (const ModesUnavailable& e) {
    using Why = ModesUnavailable::Why;
    refuse(e.why == Why::no_participation ? "ground_motion"
           : e.why == Why::no_mass        ? mass_key(spec.model)
                                          : "model",
           e.what());
  }
  return out;
}

}  // namespace condyn
