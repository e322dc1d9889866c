#include "validation/references/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace condyn {

double TrajectoryError::worst() const { return std::max({displacement, velocity, reaction}); }

namespace {

/// max |a − ref| over `scale` (absolute when the scale is 0).
double relative_max(const Eigen::MatrixXd& a, const Eigen::MatrixXd& ref, double scale) {
  if (a.size() == 0) return 0.0;
  const double diff = (a - ref).cwiseAbs().maxCoeff();
  return scale > 0.0 ? diff / scale : diff;
}

double max_abs(const Eigen::MatrixXd& x) { return x.size() > 0 ? x.cwiseAbs().maxCoeff() : 0.0; }

/// Whether row k of a trajectory with `flags` (Trajectory::near_singular) lies near a singular
/// configuration.
bool flagged(const std::vector<bool>& flags, std::size_t k) { return k < flags.size() && flags[k]; }

/// The output rows whose reactions are scored: those outside passages near a singular
/// configuration in every one of `flags`, where the multipliers are not determined by the state
/// (docs/schemes.md, "Singular configurations").
std::vector<Eigen::Index> determined_rows(std::size_t nt,
                                          std::initializer_list<const std::vector<bool>*> flags) {
  std::vector<Eigen::Index> rows;
  for (std::size_t k = 0; k < nt; ++k) {
    if (std::none_of(flags.begin(), flags.end(), [k](const auto* f) { return flagged(*f, k); })) {
      rows.push_back(static_cast<Eigen::Index>(k));
    }
  }
  return rows;
}

/// The reactions of `rows` (all of them when none is flagged).
Eigen::MatrixXd reactions_at(const Eigen::MatrixXd& reaction,
                             const std::vector<Eigen::Index>& rows) {
  if (reaction.size() == 0 || reaction.cols() == static_cast<Eigen::Index>(rows.size())) {
    return reaction;
  }
  return reaction(Eigen::all, rows);
}

}  // namespace

ErrorScales error_scales(const Trajectory& trajectory) {
  ErrorScales s;
  s.displacement = max_abs(trajectory.u);
  s.reaction = max_abs(reactions_at(
      trajectory.reaction, determined_rows(trajectory.t.size(), {&trajectory.near_singular})));
  const double span = trajectory.t.empty() ? 0.0 : trajectory.t.back() - trajectory.t.front();
  const double velocity_floor = span > 0.0 ? s.displacement / span : 0.0;
  s.velocity =
      std::max(max_abs(trajectory.v), std::isfinite(velocity_floor) ? velocity_floor : 0.0);
  s.energy = energy_error_scale(trajectory);
  return s;
}

TrajectoryError relative_error(const Trajectory& run, const Trajectory& reference) {
  return relative_error(run, reference, error_scales(reference));
}

TrajectoryError relative_error(const Trajectory& run, const Trajectory& reference,
                               const ErrorScales& scales) {
  if (run.t.size() != reference.t.size() || run.u.rows() != reference.u.rows()) {
    throw std::invalid_argument("relative_error: trajectories differ in shape");
  }
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    if (std::abs(run.t[k] - reference.t[k]) > 1e-12 * std::max(1.0, std::abs(reference.t[k]))) {
      throw std::invalid_argument("relative_error: output times differ");
    }
  }
  const auto rows = determined_rows(run.t.size(), {&run.near_singular, &reference.near_singular});
  return {relative_max(run.u, reference.u, scales.displacement),
          relative_max(run.v, reference.v, scales.velocity),
          relative_max(reactions_at(run.reaction, rows), reactions_at(reference.reaction, rows),
                       scales.reaction)};
}

double relative_energy_error(const Trajectory& run, double energy_scale) {
  const double own = relative_energy_error(run);
  if (!(own >= 0.0)) return own;  // −1: no energies; NaN: an energy beyond the double range
  const double worst = (run.energy.array() - run.energy[0]).abs().maxCoeff();
  const double scale = std::max(energy_scale, error_scales(run).energy);
  return scale > 0.0 ? worst / scale : worst;
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
