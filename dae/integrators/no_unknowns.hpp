#pragma once
/// The stepper of a DAE without unknowns (ida_integrator.cpp's integrate() runs it in place of
/// IDA).

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "dae/integrators/step_driver.hpp"

namespace condyn {

/// A problem without unknowns: master-slave elimination (a DAE) or coordinate partitioning (an
/// ODE) of a model whose every DOF is fixed or prescribed. Nothing is integrated (IDA and CVODE
/// refuse an empty vector: "initial ewt component = 0.0");
/// the rows follow from the time alone, which the loop visits as it would an integrator's steps.
/// Each step ends at the next output time or load step, or after 1/32 of the mean output interval:
/// the loop integrates the energy balance's work terms over each step by 3-point Gauss-Legendre
/// (a prescribed sin(2t) over steps of 0.25 left 6.5e-7 of the constraints' work).
class NoUnknowns final : public Stepper {
 public:
  /// `begin_segment`: the problem's, called at every restart (a load step, a drive's kink).
  NoUnknowns(std::function<void(double)> begin_segment, const std::vector<double>& output_times);
  double step(double tout) override;
  void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) override;
  [[nodiscard]] Eigen::VectorXd y() override { return {}; }
  [[nodiscard]] Eigen::VectorXd yp() override { return {}; }
  void restart(double t) override;
  void set_stop_time(double t) override { stop_ = t; }
  void fill_summary(SolveSummary& summary) override;

 private:
  std::function<void(double)> begin_segment_;
  double max_step_, t_, stop_ = 0.0;
};

}  // namespace condyn
