#include "dae/integrators/newmark_error_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace condyn {

namespace {

/// sqrt(mean_i (e_i / (rtol |u_i| + atol))²); 0 for no unknowns.
double weighted_rms(const Eigen::VectorXd& e, const Eigen::VectorXd& u, double rtol, double atol) {
  if (e.size() == 0) return 0.0;
  const Eigen::ArrayXd weighted = e.array() / (rtol * u.array().abs() + atol);
  return std::sqrt(weighted.square().mean());
}

}  // namespace

double zienkiewicz_xie_norm(double beta, const StepHistory& s, const Eigen::VectorXd& u_old,
                            double rtol, double atol) {
  Eigen::VectorXd third;  // the third derivative of u over the step
  if (s.h_before > 0.0) {
    const Eigen::VectorXd mean_before = (*s.v_old - *s.v_before) / s.h_before;
    const Eigen::VectorXd mean = (*s.v_new - *s.v_old) / s.h;
    third = (2.0 / (s.h + s.h_before)) * (mean - mean_before);
  } else {
    third = (*s.a_new - *s.a_old) / s.h;
  }
  const Eigen::VectorXd e = ((beta - 1.0 / 6.0) * s.h * s.h * s.h) * third;
  return weighted_rms(e, u_old, rtol, atol);
}

double next_newmark_step(double h, double error, bool no_growth) {
  using R = NewmarkStepRules;
  // An error of 0 (a model at rest) grows by the most allowed.
  double factor = error > 0.0 ? R::kSafety * std::cbrt(1.0 / error) : R::kMaxGrowth;
  factor = std::clamp(factor, R::kMinShrink, R::kMaxGrowth);
  if (no_growth) factor = std::min(factor, 1.0);
  if (factor >= 1.0 && factor < R::kHoldBelow) factor = 1.0;
  return factor * h;
}

double newmark_newton_fraction(double rtol) {
  const double roundoff = 100.0 * std::numeric_limits<double>::epsilon() / rtol;
  return std::min(1.0, std::max(NewmarkStepRules::kNewtonFraction, roundoff));
}

double first_newmark_step(double beta, const Eigen::VectorXd& a0, const Eigen::VectorXd& u0,
                          double rtol, double atol, double span) {
  const double size = weighted_rms(a0, u0, rtol, atol);
  if (!(size > 0.0) || !std::isfinite(size)) return span;
  return std::min(span, 1.0 / std::sqrt((beta - 1.0 / 6.0) * size));
}

}  // namespace condyn
