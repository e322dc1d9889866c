#pragma once
/// Passages of a run near a singular configuration, where the constraint Jacobian A(t, u) loses
/// rank (a parallelogram four-bar with its links collinear, the N-four-bar with its cranks
/// horizontal). There λ is not determined by the state, the reactions at output rows read far
/// off (10³ to 10⁵ times the exact ones on the parallelogram), and a scheme may leave the branch
/// it was on for another that meets it there (index1, Baumgarte and index2 on the N-four-bar),
/// with the energy balance intact. The monitor measures how close each internal step is to such a
/// configuration and whether the free motions after a passage still hold the motion before it.
/// Only models whose A depends on the state pay for it (a linear model's rank is checked once,
/// when it is built).

#include <Eigen/Dense>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "dae/interface/singular_passage.hpp"
#include "dae/linsolve/constraint_conditioning.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

/// Follows a run step by step and gathers its passages.
class SingularPassageMonitor {
 public:
  explicit SingularPassageMonitor(const MechanicalSystem& system) : conditioning_(system) {}
  /// At every internal step: the step's exact time and state.
  void step(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v);
  /// The rows' conditioning at (t, u), the one step() judges by (computed once per state).
  [[nodiscard]] double conditioning(double t, const Eigen::VectorXd& u) {
    return conditioning_(t, u);
  }
  /// The passages so far (the one the run is inside, if any, marked left_open).
  [[nodiscard]] std::vector<SingularPassage> passages() const;
  /// Whether time t, up to the last step seen, lies inside a passage so far: for t at or before
  /// that step, the answer near_singular_rows gives once the run is over.
  [[nodiscard]] bool covers(double t) const;

 private:
  ConstraintConditioning conditioning_;
  double best_ = 0.0;  ///< the largest conditioning of the steps so far
  std::vector<SingularPassage> passages_;
  bool inside_ = false;
  /// The velocity the motion before the passage would have at t: the last two steps outside it
  /// extrapolated linearly (their acceleration turns the velocity as the configuration turns, so
  /// that a smooth passage, even one crossed in a few long steps, keeps its free motion).
  [[nodiscard]] Eigen::VectorXd velocity_before(double t) const;
  /// The last two steps outside a passage (the last in [1]); times below t0 while unset.
  std::array<double, 2> outside_t_{-1.0, -1.0};
  std::array<Eigen::VectorXd, 2> outside_v_;
  std::array<double, 2> before_t_{-1.0, -1.0};  ///< those of the passage the run is in
  std::array<Eigen::VectorXd, 2> before_v_;
};

/// The summary's note: "passed 2 near-singular configurations (...): t = 1 (closest 2.1e-05,
/// rows t = 0.9 to 1.1), ...", the first five in full (empty without one). `row_times`: the
/// output times, to name the rows inside.
[[nodiscard]] std::string singular_passage_note(const std::vector<SingularPassage>& passages,
                                                const std::vector<double>& row_times);

/// A warning naming the first passage that left its branch (and how many more did), and one for
/// a run that ended inside a passage.
[[nodiscard]] std::vector<std::string> singular_passage_warnings(
    const std::vector<SingularPassage>& passages);

/// For a failed run that ended inside a passage: "; it failed inside a near-singular
/// configuration entered at t = ... (conditioning ... at t = ...)", else empty.
[[nodiscard]] std::string singular_failure_advice(const std::vector<SingularPassage>& passages);

/// For each output time, whether it lies inside a passage (between its first and last step
/// below kNearSingular times the best before it, both included): the rows whose reactions and
/// multipliers are not to be trusted.
[[nodiscard]] std::vector<bool> near_singular_rows(const std::vector<SingularPassage>& passages,
                                                   const std::vector<double>& row_times);

}  // namespace condyn
