#pragma once
/// RATTLE's stability limit. Its force update is explicit (the leapfrog, Störmer-Verlet, of the
/// unconstrained part), stable only while h ω < 2 for every mode ω of the model (the leapfrog's
/// linear stability interval; Hairer, Lubich and Wanner 2006, Geometric Numerical Integration):
/// a step beyond it makes a stiff mode grow until the forces overflow. A stiff pair (ω = 1414
/// rad/s) at h = 0.01 blew up at t = 1.35 and was advised to check its loads.

#include <optional>
#include <string>

#include "dae/formulations/model_scales.hpp"

namespace condyn {

/// What to say before (and after a failed) RATTLE run with `step`: when h ω_max ≥ 2, ω_max the
/// model's highest frequency at t = 0 (`scales`, the plan's: the constrained eigenvalues up to
/// kDenseScaleLimit DOFs, else an upper bound), the product, the largest stable step and the
/// implicit alternative; else nothing.
[[nodiscard]] std::optional<std::string> rattle_stability_warning(const ModelScales& scales,
                                                                  double step);

}  // namespace condyn
