#pragma once
/// What a run can record ([output] quantities, scene-format.md): the solver records what a scene
/// asks for (dae/run/solve.hpp, hooks_for), the writers name the columns.

#include <array>
#include <string_view>

namespace condyn {

/// A quantity a run can record; one or more output columns each.
enum class Quantity {
  displacement,
  velocity,
  acceleration,
  absolute_acceleration,  ///< u'' + r a_g(t) under [ground_motion] (columns acc_abs_<dof>)
  reaction,
  multiplier,
  drift,
  energy
};

/// The columns of the `energy` quantity, in order (docs/energy.md): T + V, the balance's error,
/// T, V, the energy dissipated, the work of the loads and of the constraint forces.
inline constexpr std::array<std::string_view, 7> kEnergyColumns = {
    "energy",     "energy_error",    "energy_kinetic", "energy_potential", "energy_dissipated",
    "work_loads", "work_constraints"};

/// The quantity's name as scenes and the command line write it ("absolute_acceleration").
[[nodiscard]] const char* to_string(Quantity q);

}  // namespace condyn
