#include "dae/formulations/rattle_stability.hpp"

#include <sstream>

namespace condyn {

std::optional<std::string> rattle_stability_warning(const ModelScales& scales, double step) {
  constexpr double kStabilityLimit = 2.0;  // h ω of the leapfrog's stability interval
  const double h_omega = step * scales.omega_max;
  if (!(h_omega >= kStabilityLimit)) return std::nullopt;
  std::ostringstream s;
  s.precision(3);
  s << "rattle's step " << step
    << " times the model's highest frequency, omega_max = " << scales.omega_max
    << " rad per time unit at t = 0 ("
    << (scales.method_max.empty() ? scales.method : scales.method_max) << "), is " << h_omega
    << ", beyond the explicit force update's stability limit h omega < 2: the stiff modes grow "
       "until the run blows up; a [solve] step below 2 / omega_max = "
    << kStabilityLimit / scales.omega_max
    << " keeps it stable, or an implicit scheme (generalized_alpha, hht) takes this step";
  return s.str();
}

}  // namespace condyn
