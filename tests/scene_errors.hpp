#pragma once
/// How the tests read a refusal of bad input: the message of the SceneError that parsing, or
/// parsing and building, throws, and the check that it names the file and the problem. One copy
/// for every test file that refuses scenes (the reader's, the builder's, the start's).

#include <doctest/doctest.h>

#include <string>

#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"

namespace condyn::test {

/// The message of the SceneError that `action` throws, or "" when it throws none.
template <class Action>
std::string scene_error_of(const Action& action) {
  try {
    action();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

/// The SceneError of parsing `text` (named `file`) and building its model, or "".
inline std::string build_error(const std::string& text, const std::string& file = "bad.toml") {
  return scene_error_of([&] { (void)build_model(parse_scene_text(text, file)); });
}

/// The SceneError of reading `text` (named `file`) alone, or "": the reader's refusals.
inline std::string parse_error(const std::string& text, const std::string& file = "bad.toml") {
  return scene_error_of([&] { (void)parse_scene_text(text, file); });
}

/// The SceneError of parsing the scene file at `path` and building its model, or "".
inline std::string file_build_error(const std::string& path) {
  return scene_error_of([&] { (void)build_model(parse_scene_file(path)); });
}

/// `message` is a refusal of bad.toml (it begins "bad.toml:", a line follows) holding `needle`.
inline void check_refusal(const std::string& message, const std::string& needle) {
  CAPTURE(message);
  CHECK(message.rfind("bad.toml:", 0) == 0);
  CHECK(message.find(needle) != std::string::npos);
}

/// Building `text` (as bad.toml) is refused, naming the file and holding `needle`.
inline void check_build_error(const std::string& text, const std::string& needle) {
  check_refusal(build_error(text), needle);
}

/// Reading `text` (as bad.toml) is refused, naming the file and holding `needle`.
inline void check_parse_error(const std::string& text, const std::string& needle) {
  check_refusal(parse_error(text), needle);
}

}  // namespace condyn::test
