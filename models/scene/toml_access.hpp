#pragma once
/// The TOML access layer of the scene reader (internal to models/: toml++ is a private dependency
/// of condyn_models). A guard run on the text before toml++ parses it, and typed getters that turn
/// a toml++ node into a value or a SceneError naming FILE:LINE and the key path. What the keys
/// mean is the section readers' business (models/scene/scene_readers.hpp).

#include <toml++/toml.h>

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "models/scene/scene_spec.hpp"

namespace condyn {

/// Throws SceneError ("FILE:LINE: a dotted key or table header nests more than 32 tables deep")
/// before toml++ sees a key it would recurse on until the stack overflows.
void check_key_depth(const std::string& text, const std::string& file);

/// Throws SceneError ("FILE:LINE: key.path: 1e-400 is nonzero but below the smallest double ...")
/// for a float written nonzero that toml++ read as 0: an underflow would pass silently for 0.
void check_number_range(const toml::table& root, const std::string& text, const std::string& file);

/// Walks the TOML tree; knows the file name so every error can say where it is. Every getter
/// either returns the value at `node` or throws SceneError naming the file, the node's line and
/// `path` (the key path as the scene writes it: "load[2].value").
class TomlAccess {
 public:
  explicit TomlAccess(std::string file) : file_(std::move(file)) {}

  [[nodiscard]] SourcePoint at(const toml::node& node, const std::string& path) const;
  [[noreturn]] void fail(const toml::node& node, const std::string& path,
                         const std::string& problem) const;
  /// Refuses the first key of `table` that is not `allowed`, listing the allowed ones.
  void check_keys(const toml::table& table, const std::string& path,
                  std::initializer_list<std::string_view> allowed) const;

  /// "solve" + "rtol" → "solve.rtol"; "" + "model" → "model".
  static std::string join(const std::string& path, const std::string& key);
  /// "load", 0 → "load[1]": 1-based, as in the scene.
  static std::string index(const std::string& path, std::size_t i);
  /// A number as messages show it (10 significant digits).
  static std::string fmt(double v);

  [[nodiscard]] const toml::table& table(const toml::node& node, const std::string& path) const;
  [[nodiscard]] const toml::array& array(const toml::node& node, const std::string& path) const;
  /// A finite float or integer.
  [[nodiscard]] double number(const toml::node& node, const std::string& path) const;
  /// A finite number > 0.
  [[nodiscard]] double positive(const toml::node& node, const std::string& path) const;
  [[nodiscard]] std::string string(const toml::node& node, const std::string& path) const;
  [[nodiscard]] long integer(const toml::node& node, const std::string& path) const;
  /// `t[key]`, or "missing required key" at `path`.`key`.
  [[nodiscard]] const toml::node& required(const toml::table& t, const std::string& path,
                                           std::string_view key) const;
  /// An array of numbers.
  [[nodiscard]] std::vector<double> numbers(const toml::node& node, const std::string& path) const;
  /// An array of arrays of numbers (rows as written; their lengths are the caller's to check).
  [[nodiscard]] std::vector<std::vector<double>> dense_matrix(const toml::node& node,
                                                              const std::string& path) const;
  /// A table { dof = number, ... }, in the order written; `lines`, when given, gets each value's
  /// line (an inline table's keys are not on its table's line).
  [[nodiscard]] std::vector<std::pair<std::string, double>> dof_values(
      const toml::node& node, const std::string& path, std::vector<int>* lines = nullptr) const;

 protected:
  std::string file_;
};

}  // namespace condyn
