#pragma once
/// The matrices the chapter prints (reference/chapter5-kinematic-constraints.txt), transcribed as
/// printed, errors included: the program assembles its own and flags every entry that differs.

#include <string>
#include <vector>

namespace condyn {

/// Which assembled quantity a printed matrix is compared with (T, G from the master-slave
/// transform; S the slave rows, all with the case's own model).
enum class ChapterQuantity {
  struck_mass,           ///< M T restricted to columns of masters: eqs. 5.6, 5.10 (all rows)
  struck_stiffness,      ///< K T: eqs. 5.6, 5.10
  transform,             ///< T: eq. 5.17
  reduced_mass,          ///< M̂ = TᵀMT
  reduced_stiffness,     ///< K̂ = TᵀKT
  reduced_loads,         ///< Tᵀ f with every step on (amplitudes)
  reduced_transfer_g,    ///< coefficient of g in f̂: −TᵀKG
  reduced_transfer_gdd,  ///< coefficient of g'' in f̂: −TᵀMG
  transfer_g,            ///< full transfer forces, coefficient of g: −KG (eq. 5.10)
  transfer_gdd,          ///< full transfer forces, coefficient of g'': −MG
  recovery_stiffness,    ///< reaction recovery (K T)_S: eqs. 5.8, 5.12
  recovery_g,            ///< (K G)_S
  recovery_gdd,          ///< (M G)_S
};

struct PrintedMatrix {
  std::string equation;  ///< "5.7"
  std::string what;      ///< what the chapter calls it
  ChapterQuantity quantity;
  int rows = 0, cols = 0;
  std::vector<double> values;  ///< row-major, as printed
  bool mass_dependent = false;
};

struct PrintedCase {
  std::string scene;    ///< embedded scene stem
  std::string section;  ///< "§5.5.1"
  std::vector<PrintedMatrix> matrices;
};

/// The five cases, §5.5.1 to §5.6.2, in order.
[[nodiscard]] const std::vector<PrintedCase>& chapter_printed();

/// Eq. 5.14 as printed: the integrated support motions, with the DOF each is written for.
struct PrintedIntegral {
  std::string dof;                   ///< label as printed
  std::vector<double> coefficients;  ///< polynomial in t, constants of integration zero
};
[[nodiscard]] const std::vector<PrintedIntegral>& chapter_eq_5_14();

}  // namespace condyn
