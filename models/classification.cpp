#include "models/classification.hpp"

namespace condyn {

std::string ConstraintClass::holonomy() const {
  if (!velocity_level) return "holonomic";
  return integrable ? "pseudo-nonholonomic (integrable)" : "nonholonomic";
}

std::vector<ConstraintClass> classify_constraints(const Model& model) {
  std::vector<ConstraintClass> out;
  for (const auto& c : model.constraints) {
    ConstraintClass k;
    k.name = c.name;
    k.single_freedom = c.coefficients.size() == 1;
    k.velocity_level = c.level == ConstraintSpec::Level::velocity;
    // A linear velocity constraint with constant coefficients, a·u' = h(t), integrates to
    // a·u = a·u(0) + ∫h (§5.5.3): every velocity constraint a scene can state today is integrable.
    k.integrable = true;
    // Time dependence and homogeneity refer to the position-level (integrated) form; the chapter
    // counts every rheonomic constraint as nonhomogeneous (§5.3.2).
    k.rheonomic = !c.position_value.is_constant();
    k.homogeneous = !k.rheonomic && c.position_value.is_zero();
    k.linear = true;
    for (const auto& [d, a] : c.coefficients)
      k.dofs.push_back(model.dof_names[static_cast<std::size_t>(d)]);
    out.push_back(std::move(k));
  }
  return out;
}

}  // namespace condyn
