#include "dae/integrators/no_unknowns.hpp"

#include <algorithm>
#include <utility>

namespace condyn {

NoUnknowns::NoUnknowns(std::function<void(double)> begin_segment,
                       const std::vector<double>& output_times)
    : begin_segment_(std::move(begin_segment)),
      max_step_((output_times.back() - output_times.front()) /
                (32.0 * static_cast<double>(std::max<std::size_t>(output_times.size() - 1, 1)))),
      t_(output_times.front()) {}

double NoUnknowns::step(double tout) {
  t_ = std::min({tout, stop_, t_ + max_step_});
  return t_;
}

void NoUnknowns::interpolate(double /*t*/, Eigen::VectorXd& y, Eigen::VectorXd& yp) {
  y.resize(0);
  yp.resize(0);
}

void NoUnknowns::restart(double t) {
  begin_segment_(t);
  t_ = t;
}

void NoUnknowns::fill_summary(SolveSummary& summary) {
  summary.steps = 0;
  summary.notes.assign(1, RunNote{RunNote::Kind::integrator,
                                  "no unknowns: every DOF is fixed or prescribed, nothing was "
                                  "integrated"});
}

}  // namespace condyn
