#include "validation/studies/drift_growth.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace condyn {

std::optional<DriftGrowth> fit_drift_growth(const std::vector<StepRecord>& steps, double floor) {
  if (steps.empty()) return std::nullopt;
  const double t_end = steps.back().t;
  const double t_from = t_end / 100.0;
  double running = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  int count = 0;
  for (const auto& s : steps) {
    running = std::max(running, s.drift_position);
    if (s.t < t_from || s.t <= 0.0 || running <= floor) continue;
    const double x = std::log(s.t), y = std::log(running);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++count;
  }
  if (count < 10) return std::nullopt;
  const double denom = count * sxx - sx * sx;
  if (!(denom > 0.0)) return std::nullopt;
  return DriftGrowth{(count * sxy - sx * sy) / denom, count, t_from, t_end};
}

namespace {

/// Least-squares slope of y against x; NaN when x does not vary.
double slope(const std::vector<double>& x, const std::vector<double>& y, std::size_t from,
             std::size_t to) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  const auto count = static_cast<double>(to - from);
  for (std::size_t i = from; i < to; ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double denom = count * sxx - sx * sx;
  return denom > 0.0 ? (count * sxy - sx * sy) / denom : std::nan("");
}

std::string figure(double x) {
  std::ostringstream s;
  s << std::setprecision(2) << x;
  return s.str();
}

}  // namespace

DriftGrowthAssessment assess_drift_growth(const std::vector<StepRecord>& steps, double floor,
                                          std::optional<double> oscillations_counted) {
  DriftGrowthAssessment out;
  if (steps.empty()) {
    out.reason = "no steps recorded";
    return out;
  }
  const double t_end = steps.back().t;
  double running = 0.0;
  std::vector<double> x, y;  // log10 t, log10 running max, where the drift exceeds roundoff
  for (const auto& s : steps) {
    running = std::max(running, s.drift_position);
    if (s.t < t_end / 100.0 || s.t <= 0.0 || running <= floor) continue;
    x.push_back(std::log10(s.t));
    y.push_back(std::log10(running));
  }
  if (x.empty()) {
    out.reason = "the drift stays at roundoff (max " + figure(running) + " <= " + figure(floor) +
                 "): no growth law to fit";
    return out;
  }
  const double oscillations =
      oscillations_counted.value_or(static_cast<double>(steps.back().velocity_reversals) / 2.0);
  if (oscillations < kMinOscillations) {
    out.reason = "the run spans " + figure(oscillations) +
                 (oscillations == 1.0 ? " oscillation" : " oscillations") +
                 " of the motion (sign changes of a velocity over the steps); "
                 "a growth law describes long runs, of 10 oscillations or more";
    return out;
  }
  const double decades = x.back() - x.front();
  const auto window = "t in [" + figure(std::pow(10.0, x.front())) + ", " + figure(t_end) + "]";
  if (decades < kMinDecades || x.size() < 4 * static_cast<std::size_t>(kMinStepsPerQuarter)) {
    out.reason = "the drift exceeds roundoff only over " + window + " (" + figure(decades) +
                 " decades, " + std::to_string(x.size()) +
                 " steps): a growth law needs at least a decade of time";
    return out;
  }
  const double whole = slope(x, y, 0, x.size());
  bool steady = std::isfinite(whole);
  std::size_t from = 0;
  for (int q = 1; q <= 4; ++q) {
    const double edge = x.front() + decades * q / 4.0;
    std::size_t to = from;
    while (to < x.size() && (x[to] <= edge || q == 4)) ++to;
    const double p = to - from >= static_cast<std::size_t>(kMinStepsPerQuarter)
                         ? slope(x, y, from, to)
                         : std::nan("");
    out.quarter_exponents.push_back(p);
    steady = steady && std::isfinite(p) && std::abs(p - whole) <= kSteadyExponentSpread;
    from = to;
  }
  if (!steady) {
    std::string qs;
    for (double p : out.quarter_exponents) qs += (qs.empty() ? "" : ", ") + figure(p);
    out.reason = "no steady power law over " + window + " (p = " + qs +
                 " over successive quarters of log t): a transient, or a drift that follows the "
                 "motion's phases; a longer run may show the law";
    return out;
  }
  out.fit = DriftGrowth{whole, static_cast<int>(x.size()), std::pow(10.0, x.front()), t_end};
  return out;
}

std::string predicted_drift_growth(Scheme scheme) {
  switch (scheme) {
    case Scheme::index1:
      return "t^2 (g'' = local errors)";
    case Scheme::index2:
      return "t (g' = local errors)";
    case Scheme::ggl:
    case Scheme::index3:
    case Scheme::newmark:
    case Scheme::hht:
    case Scheme::generalized_alpha:
    case Scheme::rattle:
      return "bounded (Newton tolerance)";
    case Scheme::baumgarte:
      return "bounded (attracting manifold)";
    case Scheme::projection:
      return "bounded (projected every step)";
    case Scheme::penalty:
      return "bounded (O(1/w) stretch)";
    case Scheme::elimination:
      return "none (constraints eliminated)";
    case Scheme::automatic:
      break;
  }
  return "";
}

}  // namespace condyn
