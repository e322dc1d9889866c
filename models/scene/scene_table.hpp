#pragma once
/// A scene given as a TOML table built in memory (the Python module's dicts, python/), beside the
/// text and file entry points of models/scene/scene_parser.hpp: the same readers, the same checks,
/// the same messages. Includes toml++: only for code that links it (the parser and the module).

#include <toml++/toml.h>

#include <Eigen/Sparse>
#include <map>
#include <string>

#include "models/scene/scene_needs.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn {

/// Matrices handed over in memory, by the name a `file` key holds in their place: a scene key
/// `{ file = NAME }` whose NAME is here takes this matrix instead of reading a Matrix Market file,
/// and gets every check a file's matrix gets (finite entries here; sizes, symmetry and definiteness
/// where the file's are checked). Nothing is densified or written.
using ArrayMatrices = std::map<std::string, Eigen::SparseMatrix<double>>;

/// Time tables handed over in memory, by the name a table time function's `file` key holds: the
/// samples as CSV text with the header `t,value` (one row per sample, 17 significant digits),
/// read by the file reader's own parser, so they get every check a file's samples get.
using ArrayTables = std::map<std::string, std::string>;

/// What a scene built in memory hands over beside its table.
struct ArrayInputs {
  ArrayMatrices matrices;
  ArrayTables tables;
};

/// Reads and validates `root` as a scene; `file` names it in messages (nodes built in memory
/// have no line, so messages read "FILE: key.path: problem"). Throws SceneError.
[[nodiscard]] SceneSpec parse_scene_table(const toml::table& root, const std::string& file,
                                          const ArrayInputs& arrays = {}, SceneNeeds needs = {});

}  // namespace condyn
