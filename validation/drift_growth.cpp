#include "validation/drift_growth.hpp"

#include <algorithm>
#include <cmath>

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

std::string predicted_drift_growth(Scheme scheme) {
  switch (scheme) {
    case Scheme::index1:
      return "t^2 (g'' = local errors)";
    case Scheme::index2:
      return "t (g' = local errors)";
    case Scheme::ggl:
    case Scheme::index3:
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
