#pragma once
/// The bridge the BDF multiplier schemes cross singular configurations with
/// (dae/integrators/passage_bridge.hpp): fixed generalized-α steps (ρ∞ = kDefaultRhoInf) on the
/// same system, from the state [u; v; ...] of the scheme's layout.

#include "dae/integrators/passage_bridge.hpp"
#include "dae/interface/solve_summary.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

/// The bridge for `system` (which must outlive it); Newton's tolerances are the run's
/// displacement tolerances (options). `linear`: M, C, K, A constant.
[[nodiscard]] PassageBridge generalized_alpha_bridge(const MechanicalSystem& system, bool linear,
                                                     const IntegratorOptions& options);

}  // namespace condyn
