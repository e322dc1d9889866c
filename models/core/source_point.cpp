#include "models/core/source_point.hpp"

namespace condyn {

std::string scene_message(const std::string& file, const SourcePoint& where,
                          const std::string& problem) {
  std::string msg = file;
  if (where.line > 0) msg += ":" + std::to_string(where.line);
  msg += ": ";
  if (!where.path.empty()) msg += where.path + ": ";
  return msg + problem;
}

}  // namespace condyn
