#pragma once
/// RATTLE (dae/integrators/rattle_step.hpp) as a Stepper of the shared loop
/// (dae/integrators/step_driver.hpp), on the fixed step grid of the Newmark family
/// (dae/integrators/fixed_step_grid.hpp): steps end on t0 + k h, a load step or the end of the
/// run off the grid is reached by a shorter step. Nothing is carried across a load step but
/// (u, v), so a restart only tells the system its new segment. Between steps, u and v come from
/// the cubic Hermite interpolant of the step's ends (step results exactly at the ends).
///
/// The state the loop sees: y = [u; v; μ] (μ the last velocity stage's multiplier, an O(h)
/// approximation of λ), y' = [v; ü; 0] with ü the interpolant's second derivative.

#include <Eigen/Dense>
#include <memory>

#include "dae/integrators/fixed_step_grid.hpp"
#include "dae/integrators/rattle_step.hpp"
#include "dae/integrators/step_driver.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

class RattleStepper : public Stepper {
 public:
  /// Starts at (t0, u0, v0), which must lie on the constraints (the model's initial state is
  /// projected there by the builder); `step` > 0.
  RattleStepper(const MechanicalSystem& system, const RattleSettings& settings, double step,
                double t0, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0);

  double step(double tout) override;
  void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) override;
  [[nodiscard]] Eigen::VectorXd y() override;
  [[nodiscard]] Eigen::VectorXd yp() override;
  void restart(double t) override;
  void set_stop_time(double t) override { stop_ = t; }
  void fill_summary(SolveSummary& summary) override;

  [[nodiscard]] long jacobian_nonzeros() const { return step_.nonzeros(); }
  [[nodiscard]] int size() const { return 2 * n_ + m_; }

 private:
  [[nodiscard]] Eigen::VectorXd pack(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                     const Eigen::VectorXd& mu) const;

  std::unique_ptr<MechanicalSystem> system_;
  int n_, m_;
  RattleStep step_;
  FixedStepGrid grid_;
  double stop_, t_, t_prev_;
  Eigen::VectorXd u_, v_, mu_, u_prev_, v_prev_, mu_prev_;
  long steps_ = 0;
  double last_step_ = 0.0;
};

}  // namespace condyn
