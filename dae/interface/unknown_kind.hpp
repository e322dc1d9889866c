#pragma once
/// What each unknown of a formulation is, for its absolute tolerance: displacements, velocities,
/// constraint multipliers (forces per unit constraint coefficient) and GGL's μ have different
/// units, so one atol cannot fit them all (dae/formulations/model_scales.hpp derives one per kind).

#include <cstddef>
#include <vector>

namespace condyn {

enum class UnknownKind { displacement, velocity, multiplier, mu };

/// [u (n); v (n); λ (m); μ (p)]: the layout every formulation's state follows (the reduced ODE
/// and the ODE schemes have no λ or μ).
[[nodiscard]] inline std::vector<UnknownKind> unknown_kinds(int n, int m = 0, int p = 0) {
  std::vector<UnknownKind> kinds;
  kinds.reserve(2 * static_cast<std::size_t>(n) + static_cast<std::size_t>(m) +
                static_cast<std::size_t>(p));
  kinds.insert(kinds.end(), static_cast<std::size_t>(n), UnknownKind::displacement);
  kinds.insert(kinds.end(), static_cast<std::size_t>(n), UnknownKind::velocity);
  kinds.insert(kinds.end(), static_cast<std::size_t>(m), UnknownKind::multiplier);
  kinds.insert(kinds.end(), static_cast<std::size_t>(p), UnknownKind::mu);
  return kinds;
}

}  // namespace condyn
