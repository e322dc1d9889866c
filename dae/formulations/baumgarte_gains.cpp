#include "dae/formulations/baumgarte_gains.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "dae/formulations/model_scales.hpp"

namespace condyn {

BaumgarteGains baumgarte_gains(const Model& model, const SolveSpec& settings) {
  BaumgarteGains g;
  std::ostringstream rule;
  rule.precision(6);
  const auto& a = settings.baumgarte_alpha;
  const auto& b = settings.baumgarte_beta;
  if (a && b) {
    g.alpha = *a;
    g.beta = *b;
    rule << "alpha = " << g.alpha << ", beta = " << g.beta << " from the scene";
  } else {
    double natural = 0.0;
    std::string why;
    if (b) {
      natural = *b;
      why = "beta from the scene";
    } else if (const ModelScales s = model_scales(model); s.omega_max > 0.0) {
      natural = s.omega_max;
      why = "beta = highest constrained natural frequency (" + s.method + ")";
    } else {
      // No stiffness, no force, no motion: the run's length is the only time scale left.
      natural = 2.0 * std::numbers::pi / settings.t_end;
      why = "beta = 2 pi / t_end (no constrained frequency)";
    }
    g.beta = natural;
    g.alpha = a ? *a : natural;  // critical damping of the constraint error
    rule << "alpha = " << g.alpha << ", beta = " << g.beta << " (" << why
         << (a ? ", alpha from the scene)" : ", alpha = beta: critical damping)");
  }
  g.rule = rule.str();
  return g;
}

}  // namespace condyn
