#pragma once
/// The error yardstick: the exact response of a linear time-invariant model whose constraints are
/// linear and integrable. Built independently of the elimination path: the constrained motion is
/// written u = N q + A⁺ g(t) with N an orthonormal basis of null(A) (from a QR factorisation of
/// Aᵀ) and A⁺ = Aᵀ(AAᵀ)⁻¹, so neither the slave choice nor the transformation T is shared. The
/// reduced system NᵀMN q'' + NᵀCN q' + NᵀKN q = Nᵀ(f − K A⁺g − C A⁺g' − M A⁺g'') is solved in
/// closed form by modal superposition (validation/references/modal_exact.hpp).

#include <vector>

#include "dae/run/trajectory.hpp"
#include "models/core/model.hpp"
#include "validation/references/modal_exact.hpp"

namespace condyn {

/// Above this many DOFs the dense modal solution is not attempted (2,000: a 32 MB basis and an
/// eigenproblem of seconds; 10^4 would take minutes and GBs).
inline constexpr int kMaxExactDofs = 2000;

/// Exact trajectory at `times`. Throws ExactSolutionUnavailable when the reduced system has no
/// modal closed form (singular reduced mass, non-classical damping) or the model has more than
/// kMaxExactDofs DOFs (the message says so; compare then uses a tight-tolerance run).
[[nodiscard]] Trajectory exact_trajectory(const Model& model, const std::vector<double>& times);

}  // namespace condyn
