#pragma once
/// The BDF schemes across singular configurations: where the constraint rows lose rank (the
/// N-four-bar with its cranks horizontal), IDA's corrector and error test see the multipliers of
/// the vanishing row combination undetermined and its steps collapse, or a scheme steps onto the
/// other branch that meets there (docs/limitations.md). A bridge carries the run across: from
/// the last step before the passage, fixed steps of the generalized-α method (index 3, Newton
/// with a backward-error test, which passes A02's passages on their branch at any step,
/// docs/validation.md) until the rows' conditioning has risen past the passage, then the BDF
/// integrator restarts there from a consistent state (velocities onto the velocity rows,
/// multipliers and accelerations recomputed) and goes on.
///
/// A bridge starts where an accepted BDF step's conditioning falls below
/// SingularPassage::kNearSingular times the best of the run so far, or where the BDF integrator
/// fails at a conditioning below kFailureFraction of that best (GGL on A02 fails a little before
/// the passage); it ends at the first step whose conditioning is at least kExitGrowth times its
/// start's and at least PassageBridge::exit_fraction of the best. Its step is the largest of the
/// last BDF steps, divided by kRefinement: a second-order method over a span the BDF method crossed
/// at order up to 5.

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dae/integrators/step_driver.hpp"
#include "dae/interface/singular_passage.hpp"

namespace condyn {

/// What the formulation whose run is bridged supplies.
struct PassageBridge {
  /// The conditioning of the constraint rows (dae/linsolve/constraint_conditioning.hpp) at time t
  /// and state y, in the problem's layout.
  std::function<double(double t, const Eigen::VectorXd& y)> conditioning;
  /// A stepper that starts at (t, y) (the problem's layout) with the fixed step h. Its y and y'
  /// begin as the problem's: [u; v] and λ where the problem has them, its components past the
  /// problem's size dropped, the problem's past its own (GGL's μ) 0 while it runs.
  std::function<std::unique_ptr<Stepper>(double t, const Eigen::VectorXd& y, double h)> start;
  /// Restarts the BDF integrator at (t, y) (the problem's layout, y' from the state).
  std::function<void(double t, const Eigen::VectorXd& y)> restart_at;
  /// The name the notes give the bridge's method.
  std::string method = "generalized-α";
  /// The fraction of the run's best conditioning a bridge must regain before the BDF integrator
  /// takes over again. Projection sets a larger one: CVODE restarted at the threshold crawls at
  /// order 1 with tiny steps, its error estimate held up by the roundoff of its right-hand side
  /// (a saddle-point solve with rows still near-singular); IDA's schemes keep the threshold,
  /// since a longer bridge adds its own error (docs/schemes.md, "The bridge").
  double exit_fraction = SingularPassage::kNearSingular;
};

/// One bridged passage.
struct BridgedPassage {
  double t_start = 0.0, t_end = 0.0;
  double step = 0.0;
  long steps = 0;
  bool on_failure = false;  ///< started after the BDF integrator failed (else on entering)
};

/// The BDF stepper `inner` with bridges across singular configurations.
class BridgedStepper final : public Stepper {
 public:
  static constexpr double kFailureFraction = 0.25;
  /// The growth of the conditioning from a bridge's start that ends it (with exit_fraction).
  static constexpr double kExitGrowth = 2.0;
  static constexpr double kRefinement = 16.0;
  /// BDF steps whose sizes give the bridge's step.
  static constexpr std::size_t kRecentSteps = 20;

  /// `size`: the problem's unknowns; (t0, y0) its initial state.
  BridgedStepper(Stepper& inner, PassageBridge bridge, int size, double t0,
                 const Eigen::VectorXd& y0);

  double step(double tout) override;
  void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) override;
  [[nodiscard]] Eigen::VectorXd y() override;
  [[nodiscard]] Eigen::VectorXd yp() override;
  void restart(double t) override;
  [[nodiscard]] bool wants_restart(double t) override;
  void set_stop_time(double t) override;
  void fill_summary(SolveSummary& summary) override;

  [[nodiscard]] const std::vector<BridgedPassage>& passages() const { return passages_; }

 private:
  /// The bridge's stepper from (t, y), which the inner stepper reached.
  void begin(double t, const Eigen::VectorXd& y, bool on_failure);
  /// A bridge state in the problem's layout: cut or padded with zeros to its size.
  [[nodiscard]] Eigen::VectorXd padded(const Eigen::VectorXd& x) const;

  Stepper& inner_;
  PassageBridge bridge_;
  int size_;
  double best_ = 0.0;           ///< the largest conditioning of the steps so far
  double t_last_;               ///< the time of the last accepted BDF step
  std::vector<double> recent_;  ///< the last BDF step sizes, up to kRecentSteps
  double stop_ = 0.0;
  bool pending_ = false;  ///< the last BDF step entered a passage: bridge from it at the next step
  std::unique_ptr<Stepper> active_;  ///< the bridge's stepper while one runs
  double exit_ = 0.0;                ///< the conditioning at which the active bridge ends
  bool done_ = false;                ///< the active bridge reached exit_
  std::vector<BridgedPassage> passages_;
  SolveSummary bridged_;  ///< the counters of the bridges that ended
};

/// drive() on `inner`, across singular configurations on bridges where `bridge` is given (its
/// restart_at set to inner.restart_from); `size`: the problem's unknowns.
template <class Inner>
RawTrajectory drive_bridged(Inner& inner, const PassageBridge* bridge, int size, double t0,
                            const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0,
                            const IntegratorOptions& options, SolveSummary& summary) {
  if (!bridge) return drive(inner, y0, yp0, options, summary);
  PassageBridge across = *bridge;
  across.restart_at = [&inner](double t, const Eigen::VectorXd& y) { inner.restart_from(t, y); };
  BridgedStepper bridged(inner, std::move(across), size, t0, y0);
  return drive(bridged, y0, yp0, options, summary);
}

}  // namespace condyn
