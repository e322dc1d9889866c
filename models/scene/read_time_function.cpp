#include "models/scene/scene_readers.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace condyn {

TimeTerm SceneReader::term(const toml::node& node, const std::string& path) const {
  const auto& t = table(node, path);
  const std::string type = string(required(t, path, "type"), join(path, "type"));
  TimeTerm term;
  auto opt = [&](std::string_view key, double dflt) {
    const auto* n = t.get(key);
    return n ? number(*n, join(path, std::string(key))) : dflt;
  };
  if (type == "step") {
    check_keys(t, path, {"type", "amplitude", "start"});
    term.kind = TimeTerm::Kind::step;
    term.amplitude = opt("amplitude", 1.0);
    term.start = opt("start", 0.0);
  } else if (type == "polynomial") {
    check_keys(t, path, {"type", "coefficients"});
    term.kind = TimeTerm::Kind::polynomial;
    term.coefficients = numbers(required(t, path, "coefficients"), join(path, "coefficients"));
    if (term.coefficients.empty()) fail(node, join(path, "coefficients"), "must not be empty");
  } else if (type == "harmonic") {
    check_keys(t, path, {"type", "amplitude", "omega", "phase"});
    term.kind = TimeTerm::Kind::harmonic;
    term.amplitude = opt("amplitude", 1.0);
    term.omega = number(required(t, path, "omega"), join(path, "omega"));
    term.phase = opt("phase", 0.0);
  } else if (type == "exponential") {
    check_keys(t, path, {"type", "amplitude", "rate"});
    term.kind = TimeTerm::Kind::exponential;
    term.amplitude = opt("amplitude", 1.0);
    term.rate = number(required(t, path, "rate"), join(path, "rate"));
  } else if (type == "table") {
    check_keys(t, path, {"type", "file", "column", "scale"});
    term.kind = TimeTerm::Kind::table;
    term.amplitude = opt("scale", 1.0);
    std::string column;
    if (const auto* c = t.get("column")) {
      column = string(*c, join(path, "column"));
      if (column.empty()) fail(*c, join(path, "column"), "must not be empty");
    }
    term.table = table_file(required(t, path, "file"), join(path, "file"), column);
  } else if (type == "displacement_record") {
    return displacement_record(t, path);
  } else {
    fail(*t.get("type"), join(path, "type"),
         "unknown time function '" + type +
             "' (expected step, polynomial, harmonic, exponential, table or "
             "displacement_record)");
  }
  return term;
}

std::string SceneReader::file_name(const toml::node& node, const std::string& key) const {
  std::string file = string(node, key);
  if (file.empty()) fail(node, key, "the file name is empty");
  // The system would read the name only up to the NUL (\u0000 in TOML): another file.
  if (file.find('\0') != std::string::npos) {
    fail(node, key, "the file name holds a NUL character (\\u0000)");
  }
  return file;
}

std::shared_ptr<const TimeTable> SceneReader::table_file(const toml::node& file_node,
                                                         const std::string& key,
                                                         const std::string& column,
                                                         std::size_t min_samples) const {
  const std::string file = file_name(file_node, key);
  if (arrays_ != nullptr) {
    if (const auto it = arrays_->tables.find(file); it != arrays_->tables.end()) {
      // Samples handed over in memory (the Python module's arrays): row k is the text's line k+1.
      try {
        auto table = std::make_shared<TimeTable>(parse_time_table(it->second, column, min_samples));
        table->file = file;
        return table;
      } catch (const TimeTableError& e) {
        fail(file_node, key,
             file + (e.line() > 1 ? ": row " + std::to_string(e.line() - 1) : std::string()) +
                 ": " + e.what());
      }
    }
  }
  // Relative to the scene file's folder (a scene given as text: the working directory), as the
  // Matrix Market files (read_matrix_files.cpp).
  const std::filesystem::path resolved =
      std::filesystem::path(file_).parent_path() / std::filesystem::path(file);
  input_files_.push_back(resolved.string());
  try {
    auto table =
        std::make_shared<TimeTable>(read_time_table(resolved.string(), column, min_samples));
    table->file = file;
    return table;
  } catch (const TimeTableError& e) {
    const std::string where =
        resolved.string() + (e.line() > 0 ? ":" + std::to_string(e.line()) : std::string());
    fail(file_node, key, where + ": " + e.what());
  }
}

TimeFunction SceneReader::time_function(const toml::node& node, const std::string& path) const {
  if (node.is_number()) return TimeFunction::constant(number(node, path));
  if (node.is_table()) return TimeFunction({term(node, path)});
  if (const auto* arr = node.as_array()) {
    std::vector<TimeTerm> terms;
    for (std::size_t i = 0; i < arr->size(); ++i)
      terms.push_back(term(*arr->get(i), index(path, i)));
    if (terms.empty()) fail(node, path, "an empty list is not a time function (write 0)");
    return TimeFunction(std::move(terms));
  }
  fail(node, path, "expected a number, a time-function table or a list of them");
}

}  // namespace condyn
