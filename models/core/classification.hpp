#pragma once
/// Constraint classification in the chapter's terms (Tables 5.1 and 5.2).

#include <string>
#include <vector>

#include "models/core/model.hpp"

namespace condyn {

struct ConstraintClass {
  std::string name;
  bool single_freedom = true;   ///< SFC (one DOF) or MFC
  bool velocity_level = false;  ///< written on velocities (form 5.2)
  bool integrable = true;       ///< velocity-level and reducible to (5.1): pseudo-nonholonomic
  bool rheonomic = false;       ///< explicit time dependence (of the integrated form)
  bool homogeneous = true;      ///< no right-hand side (of the integrated form)
  bool linear = true;
  std::vector<std::string> dofs;
  /// Nonlinear rows: what the row says and, for velocity rows, the integrability evidence
  /// (Frobenius: a · (∇ × a) at the initial state).
  std::string note;

  /// "holonomic", "pseudo-nonholonomic (integrable)" or "nonholonomic".
  [[nodiscard]] std::string holonomy() const;
};

/// Classifies every constraint of the model, in scene order. Nonlinear rows are probed for time
/// dependence inside the run, at 0 and 0.5 t_end + 0.1234. The cost is linear in the model: the
/// nonlinear rows share one evaluator (one clone() of the model's system), four evaluations of
/// A and two of each residual; only the Frobenius test of a nonlinear velocity-level row evaluates
/// the system once more, for that row.
[[nodiscard]] std::vector<ConstraintClass> classify_constraints(const Model& model, double t_end);

}  // namespace condyn
