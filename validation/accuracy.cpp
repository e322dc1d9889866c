#include "validation/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace condyn {

double TrajectoryError::worst() const { return std::max({displacement, velocity, reaction}); }

namespace {

double relative_max(const Eigen::MatrixXd& a, const Eigen::MatrixXd& ref, double floor = 0.0) {
  if (a.size() == 0) return 0.0;
  const double diff = (a - ref).cwiseAbs().maxCoeff();
  const double scale = std::max(ref.cwiseAbs().maxCoeff(), floor);
  return scale > 0.0 ? diff / scale : diff;
}

}  // namespace

TrajectoryError relative_error(const Trajectory& run, const Trajectory& reference) {
  if (run.t.size() != reference.t.size() || run.u.rows() != reference.u.rows()) {
    throw std::invalid_argument("relative_error: trajectories differ in shape");
  }
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    if (std::abs(run.t[k] - reference.t[k]) > 1e-12 * std::max(1.0, std::abs(reference.t[k]))) {
      throw std::invalid_argument("relative_error: output times differ");
    }
  }
  // Velocities against at least the displacement scale over the run's span: a structure at rest
  // (a static start) has reference velocities of roundoff, 1e-17, which would make a run's
  // exact zeros an error of 1. Any motion of angular frequency ω over a span D ≥ 2π/ω has
  // max |v| ≈ ω max |u| > max |u| / D, so only quasi-static runs meet the floor.
  const double span = reference.t.empty() ? 0.0 : reference.t.back() - reference.t.front();
  const double velocity_floor =
      span > 0.0 && reference.u.size() > 0 ? reference.u.cwiseAbs().maxCoeff() / span : 0.0;
  return {relative_max(run.u, reference.u),
          relative_max(run.v, reference.v, std::isfinite(velocity_floor) ? velocity_floor : 0.0),
          relative_max(run.reaction, reference.reaction)};
}

}  // namespace condyn

namespace condyn {

double mescd(const Eigen::VectorXd& y, const Eigen::VectorXd& ref, double rtol, double atol) {
  constexpr double kExact = 17.0;
  double digits = kExact;
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    const double err = std::abs(y[i] - ref[i]) / (atol / rtol + std::abs(ref[i]));
    if (err > 0.0) digits = std::min(digits, -std::log10(err));
  }
  return digits;
}

std::string ReferenceScore::describe() const {
  std::ostringstream s;
  s.precision(2);
  s << std::fixed;
  const auto part = [&](double d, int trusted) {
    if (d >= trusted) {
      s << ">= " << trusted << " (the reference's limit)";
    } else {
      s << d;
    }
  };
  part(digits_u, trusted_u);
  s << " digits in positions";
  if (digits_v) {
    s << ", ";
    part(*digits_v, trusted_v);
    s << " in velocities";
  }
  return s.str();
}

std::optional<ReferenceScore> score_at_output(const Model& model, const Trajectory& run,
                                              std::size_t k, double rtol, double atol) {
  if (!model.reference || k >= run.t.size()) return std::nullopt;
  const double t = run.t[k];
  const auto ref = model.reference(t);
  if (!ref) return std::nullopt;
  ReferenceScore score;
  score.t = t;
  score.source = ref->source;
  score.trusted_u = ref->digits_u;
  score.trusted_v = ref->digits_v;
  const auto col = static_cast<Eigen::Index>(k);
  score.digits_u = mescd(run.u.col(col), ref->u, rtol, atol);
  if (ref->v.size() > 0) score.digits_v = mescd(run.v.col(col), ref->v, rtol, atol);
  return score;
}

std::optional<ReferenceScore> score_against_reference(const Model& model, const Trajectory& run,
                                                      double rtol, double atol) {
  if (run.t.empty()) return std::nullopt;
  return score_at_output(model, run, run.t.size() - 1, rtol, atol);
}

}  // namespace condyn
