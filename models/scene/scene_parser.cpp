#include "models/scene/scene_parser.hpp"

#include <toml++/toml.h>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "models/scene/scene_readers.hpp"
#include "models/scene/scene_table.hpp"

namespace condyn {

std::string no_checks_message(const std::string& file) {
  return scene_message(file, {}, "has no [[check]] table: nothing to check");
}

SceneSpec SceneReader::read(const toml::table& root, SceneNeeds needs) const {
  if (needs.checks && !root.contains("check")) throw SceneError(no_checks_message(file_));
  SceneSpec spec;
  spec.file = file_;
  check_keys(root, "",
             {"name", "units", "model", "load", "ground_motion", "constraint", "constraint_block",
              "initial", "solve", "output", "check", "derived", "body", "joint", "force"});
  if (const auto* n = root.get("name")) spec.name = string(*n, "name");
  if (const auto* n = root.get("units")) {
    const std::string u = string(*n, "units");
    if (u != "SI") {
      fail(*n, "units",
           "'" + u +
               "' is not a unit system condyn knows: \"SI\" (metres, kilograms, seconds) is the "
               "one it names; leave the key out for any other consistent units");
    }
    spec.si_units = true;
  }
  read_model(required(root, "", "model"), spec.model);
  read_mechanism_sections(root, spec.model);

  if (const auto* n = root.get("load")) read_loads(*n, spec.loads);
  if (const auto* n = root.get("ground_motion")) {
    read_ground_motion(*n, spec.model, spec.ground_motion);
  }
  if (const auto* n = root.get("constraint")) read_constraints(*n, spec.constraints);
  if (const auto* n = root.get("constraint_block")) {
    read_constraint_blocks(*n, spec.constraint_blocks);
  }
  if (const auto* n = root.get("initial")) read_initial(*n, spec.initial);
  read_solve(required(root, "", "solve"), spec.solve);
  if (spec.solve.output_step > spec.solve.t_end) {
    fail(*root.get("solve")->as_table()->get("output_step"), "solve.output_step",
         "is larger than t_end (" + fmt(spec.solve.output_step) + " > " + fmt(spec.solve.t_end) +
             ")");
  }
  if (const auto* n = root.get("output")) read_output(*n, spec.output);
  if (const auto* n = root.get("check")) read_checks(*n, spec.solve, spec.checks);
  if (const auto* n = root.get("derived")) read_derived(*n, spec.derived);
  check_mechanism_names(root, spec);
  check_columns(root, spec);
  spec.input_files = input_files_;
  return spec;
}

SceneSpec parse_scene_text(const std::string& text, const std::string& file, SceneNeeds needs) {
  check_key_depth(text, file);
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw SceneError(scene_message(file, SourcePoint{"", static_cast<int>(e.source().begin.line)},
                                   "TOML syntax error: " + std::string(e.description())));
  }
  check_number_range(root, text, file);
  return SceneReader(file).read(root, needs);
}

SceneSpec parse_scene_table(const toml::table& root, const std::string& file,
                            const ArrayInputs& arrays, SceneNeeds needs) {
  return SceneReader(file, arrays).read(root, needs);
}

SceneSpec parse_scene_file(const std::string& path, SceneNeeds needs) {
  // `condyn check a.toml ''` printed ": cannot open the scene file", naming nothing.
  if (path.empty()) throw SceneError("'': an empty scene file name: name a scene file");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw SceneError(path + ": is a folder (name a scene file)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    // Why, as the system says it: missing, permission denied, ...
    const int error = errno;
    throw SceneError(path + ": cannot open the scene file" +
                     (error != 0
                          ? " (" + std::error_code(error, std::generic_category()).message() + ")"
                          : std::string()));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read the scene file");
  return parse_scene_text(text.str(), path, needs);
}

}  // namespace condyn
