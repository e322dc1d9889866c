#pragma once
/// The Chaplygin sleigh: a rigid body in the plane, coordinates u = (x, y, θ) of its centre of
/// mass and heading, mass m and moment of inertia J about the centre of mass, on a knife edge at
/// the contact point P = (x, y) + a (cos θ, sin θ) that may roll along the body axis but not slide
/// sideways:
///
///   −sin θ x' + cos θ y' + a θ' = 0      (velocity of P normal to the axis vanishes)
///
/// A(u) = (−sin θ, cos θ, a) is not integrable: a · (∇ × a) = −1 ≠ 0 (Frobenius), so no position
/// constraint stands behind it; it is nonholonomic, and only multiplier schemes can treat it.
/// γ = θ'(cos θ x' + sin θ y'). Loads are the scene's generalized forces on x, y, θ.

#include <memory>
#include <vector>

#include "models/core/mechanical_system.hpp"
#include "models/core/model.hpp"

namespace condyn {

struct SleighParameters {
  double mass = 1.0, inertia = 1.0, contact_offset = 0.0;
  std::vector<Load> loads;
};

[[nodiscard]] std::shared_ptr<const MechanicalSystem> make_sleigh(SleighParameters parameters);

}  // namespace condyn
