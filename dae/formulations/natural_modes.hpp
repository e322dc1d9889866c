#pragma once
/// The natural modes of a linear model under its constraints (`condyn modes`, condyn.modes): the
/// lowest eigenpairs of K φ = ω² M φ on the motions the constraints allow, A φ = 0. The
/// constraints are eliminated as elimination's reduced system does (dae/formulations/
/// reduced_system.hpp: u = T û, K̂ = TᵀKT, M̂ = TᵀMT; the right-hand sides g(t) move no mode), the
/// pencil (K̂, M̂) is solved by models/core/pencil_modes.hpp, and the shapes are expanded to
/// every DOF, φ = T φ̂.
///
/// Under [ground_motion] with influence vector r, mode j's participation is Γ_j = φ_jᵀ M r
/// (φ_jᵀ M φ_j = 1) and its effective mass Γ_j²; the total mass along r is the sum over every
/// mode, L̂ᵀ M̂⁻¹ L̂ with L̂ = Tᵀ M r (rᵀ M r when r is a motion the constraints allow; a support's
/// own mass, which no mode moves, is not in it), so the ratios of all modes sum to 1.

#include <Eigen/Dense>
#include <limits>
#include <optional>
#include <stdexcept>

#include "models/core/model.hpp"
#include "models/core/pencil_modes.hpp"

namespace condyn {

struct NaturalModes {
  Eigen::VectorXd omega;       ///< ω_j (rad per time unit), ascending
  Eigen::MatrixXd shapes;      ///< n x count over the model's DOFs, φᵀMφ = 1, largest entry > 0
  Eigen::VectorXd mass_ratio;  ///< Γ_j² / total mass along r; empty without [ground_motion]
  Eigen::VectorXd mass_ratio_cumulative;  ///< its running sum over modes 1..j
  double total_mass = 0.0;                ///< along r (0 without [ground_motion])
  int available = 0;                      ///< modes of the constrained model (its DOFs with mass)
  bool dense = false;                     ///< the dense path, not Lanczos
};

inline constexpr double kTwoPi = 6.283185307179586476925286766559;
/// Cycles per time unit of a mode of ω rad per time unit.
[[nodiscard]] inline double mode_frequency(double omega) { return omega / kTwoPi; }
/// Its period; infinity for a zero-frequency mode (a rigid motion).
[[nodiscard]] inline double mode_period(double omega) {
  return omega > 0.0 ? kTwoPi / omega : std::numeric_limits<double>::infinity();
}

/// A count out of [1, the modes the constrained model has]: the message says how many it has.
class ModeCountError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Modes given when no count is asked for: the lowest ten (all, when the model has fewer).
inline constexpr int kDefaultModeCount = 10;

/// The `count` lowest modes (default kDefaultModeCount, or all the model has). Throws
/// ModesUnavailable for a nonlinear model (its modes depend on its state and constraint forces: not
/// linearized here), a model without mass, an unstable one or massless DOFs nothing holds;
/// ModeCountError for a count out of range; SchemeNotApplicable when a coupled group of constraints
/// is too large to eliminate.
[[nodiscard]] NaturalModes natural_modes(const Model& model, std::optional<int> count,
                                         ModeSolver solver = ModeSolver::automatic);

}  // namespace condyn
