#include "dae/baumgarte_gains.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "dae/elimination.hpp"

namespace condyn {

namespace {

/// Highest natural frequency of the constrained system, or nothing when it is not defined.
std::optional<double> highest_constrained_frequency(const Model& model) {
  try {
    const ReducedSystem r = reduce(model);
    const Eigen::MatrixXd M(r.M), K(r.K);
    if (M.rows() == 0) return std::nullopt;
    Eigen::LLT<Eigen::MatrixXd> llt(M);
    if (llt.info() != Eigen::Success) return std::nullopt;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M,
                                                                        Eigen::EigenvaluesOnly);
    if (eig.info() != Eigen::Success) return std::nullopt;
    const double k_max = eig.eigenvalues().maxCoeff();
    return k_max > 0.0 ? std::optional<double>(std::sqrt(k_max)) : std::nullopt;
  } catch (const std::exception&) {
    return std::nullopt;  // no elimination possible: fall back to the output step
  }
}

}  // namespace

BaumgarteGains baumgarte_gains(const Model& model) {
  BaumgarteGains g;
  std::ostringstream rule;
  rule.precision(6);
  const auto& a = model.solve.baumgarte_alpha;
  const auto& b = model.solve.baumgarte_beta;
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
    } else if (const auto w = highest_constrained_frequency(model)) {
      natural = *w;
      why = "beta = highest constrained natural frequency";
    } else {
      natural = 2.0 * std::numbers::pi / model.solve.output_step;
      why = "beta = 2 pi / output_step (no constrained frequency)";
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
