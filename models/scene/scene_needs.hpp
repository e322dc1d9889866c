#pragma once
/// What a caller needs of a scene beyond its being valid (models/scene/scene_parser.hpp). The
/// parser refuses a scene without it before reading any file the scene names: a matrix model's
/// files can take seconds and gigabytes to read.

namespace condyn {

struct SceneNeeds {
  /// [[check]] tables (`condyn check`, Python's check()).
  bool checks = false;
};

}  // namespace condyn
