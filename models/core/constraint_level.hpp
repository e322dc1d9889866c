#pragma once
/// The level a linear constraint row acts at (scene-format.md, [[constraint]] level): a position
/// row A u = g(t), or a velocity row A_v u' = h(t).

namespace condyn {

enum class ConstraintLevel { position, velocity };

}  // namespace condyn
