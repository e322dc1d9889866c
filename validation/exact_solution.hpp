#pragma once
/// The error yardstick: the exact response of a linear time-invariant model whose constraints are
/// linear and integrable. Built independently of the elimination path: the constrained motion is
/// written u = N q + A⁺ g(t) with N an orthonormal basis of null(A) (from a QR factorisation of
/// Aᵀ) and A⁺ = Aᵀ(AAᵀ)⁻¹, so neither the slave choice nor the transformation T is shared. The
/// reduced system NᵀMN q'' + NᵀCN q' + NᵀKN q = Nᵀ(f − K A⁺g − C A⁺g' − M A⁺g'') is solved in
/// closed form by modal superposition (validation/modal_exact.hpp).

#include <vector>

#include "dae/trajectory.hpp"
#include "models/model.hpp"
#include "validation/modal_exact.hpp"

namespace condyn {

/// Exact trajectory at `times`. Throws ExactSolutionUnavailable when the reduced system has no
/// modal closed form (singular reduced mass, non-classical damping).
[[nodiscard]] Trajectory exact_trajectory(const Model& model, const std::vector<double>& times);

}  // namespace condyn
