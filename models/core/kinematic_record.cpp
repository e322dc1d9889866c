#include "models/core/kinematic_record.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace condyn {

namespace {

/// The coefficients c_0 … c_5 in τ = t − t_k of the quintic on [t_k, t_{k+1}] with the samples'
/// d, v, a at both ends: c_0..c_2 from the left end, c_3..c_5 from the defects Δd, Δv, Δa of the
/// left end's quadratic at the right end (the 3 × 3 system solved in closed form).
std::array<double, 6> piece(const KinematicRecord& r, std::size_t k) {
  const double h = r.times[k + 1] - r.times[k];
  const double d0 = r.displacement[k], v0 = r.velocity[k], a0 = r.acceleration[k];
  const double dd = r.displacement[k + 1] - (d0 + h * (v0 + 0.5 * h * a0));
  const double dv = (r.velocity[k + 1] - (v0 + h * a0)) * h;
  const double da = (r.acceleration[k + 1] - a0) * h * h;
  const double h3 = h * h * h;
  return {d0,
          v0,
          0.5 * a0,
          (20.0 * dd - 8.0 * dv + da) / (2.0 * h3),
          (-30.0 * dd + 14.0 * dv - 2.0 * da) / (2.0 * h3 * h),
          (12.0 * dd - 6.0 * dv + da) / (2.0 * h3 * h * h)};
}

/// d^order/dτ^order Σ c_j τ^j (Horner on the differentiated coefficients).
double polynomial(const std::array<double, 6>& c, int order, double tau) {
  double result = 0.0;
  for (int j = 5; j >= order; --j) {
    double factor = 1.0;
    for (int i = 0; i < order; ++i) factor *= static_cast<double>(j - i);
    result = result * tau + factor * c[static_cast<std::size_t>(j)];
  }
  return result;
}

/// bound[order] = max over the pieces of Σ_j |c_j| j!/(j − order)! h^(j − order), which bounds
/// |f^(order)| on the piece (every term at its largest |τ| = h).
void set_bounds(KinematicRecord& r) {
  r.bound = {0.0, 0.0, 0.0};
  for (std::size_t k = 0; k + 1 < r.samples(); ++k) {
    std::array<double, 6> c = piece(r, k);
    for (double& x : c) x = std::abs(x);
    const double h = r.times[k + 1] - r.times[k];
    for (int order = 0; order <= 2; ++order) {
      const auto o = static_cast<std::size_t>(order);
      r.bound[o] = std::max(r.bound[o], polynomial(c, order, h));
    }
  }
}

/// The first sample of `other` whose time differs from `reference`'s, as a RecordMismatch.
void require_same_times(const TimeTable& reference, const TimeTable& other, const char* what) {
  const std::size_t n = std::min(reference.samples(), other.samples());
  for (std::size_t k = 0; k < n; ++k) {
    if (other.times[k] == reference.times[k]) continue;
    std::ostringstream s;
    s.precision(17);
    s << "the " << what << " record's sample " << k + 1 << " is at t = " << other.times[k]
      << ", the displacement's (" << reference.file << ") at t = " << reference.times[k]
      << ": the three records must share their sample times";
    throw RecordMismatch(what, other.file, other.lines.empty() ? 0 : other.lines[k], s.str());
  }
  if (other.samples() != reference.samples()) {
    std::ostringstream s;
    s << "the " << what << " record has " << other.samples() << " samples, the displacement's ("
      << reference.file << ") " << reference.samples()
      << ": the three records must share their sample times";
    const std::size_t k = n < other.samples() ? n : n - 1;
    throw RecordMismatch(what, other.file, other.lines.empty() ? 0 : other.lines[k], s.str());
  }
}

/// v and d at every sample of a piecewise linear acceleration, integrated exactly from rest.
void integrate(KinematicRecord& r) {
  const std::size_t n = r.samples();
  r.velocity.assign(n, 0.0);
  r.displacement.assign(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double h = r.times[k + 1] - r.times[k];
    const double a0 = r.acceleration[k], a1 = r.acceleration[k + 1];
    r.velocity[k + 1] = r.velocity[k] + 0.5 * h * (a0 + a1);
    r.displacement[k + 1] = r.displacement[k] + h * r.velocity[k] + h * h * (2.0 * a0 + a1) / 6.0;
  }
}

}  // namespace

double KinematicRecord::derivative(int order, double t) const {
  if (order < 0 || order > 2) throw std::invalid_argument("record derivative order must be 0..2");
  // Held still outside [t_0, t_last]; at the end samples themselves, the record's own values.
  if (t < times.front()) return order == 0 ? displacement.front() : 0.0;
  if (t > times.back()) return order == 0 ? displacement.back() : 0.0;
  const auto after =
      static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const std::size_t k = std::min(after - 1, samples() - 2);  // t_last: the last piece's end
  return polynomial(piece(*this, k), order, t - times[k]);
}

KinematicRecord record_from_triple(const TimeTable& displacement, const TimeTable& velocity,
                                   const TimeTable& acceleration, const std::string& source) {
  require_same_times(displacement, velocity, "velocity");
  require_same_times(displacement, acceleration, "acceleration");
  KinematicRecord r;
  r.source = source;
  r.times = displacement.times;
  r.displacement = displacement.values;
  r.velocity = velocity.values;
  r.acceleration = acceleration.values;
  set_bounds(r);
  return r;
}

KinematicRecord record_from_acceleration(const TimeTable& acceleration, Baseline baseline,
                                         const std::string& source) {
  KinematicRecord r;
  r.source = source;
  r.times = acceleration.times;
  r.acceleration = acceleration.values;
  integrate(r);
  if (baseline == Baseline::linear) {
    // With V, D the uncorrected end velocity and displacement over T = t_last − t_0, subtracting
    // c0 + c1 τ from a removes c0 T + c1 T²/2 from V and c0 T²/2 + c1 T³/6 from D: both vanish
    // for c1 = (6 V T − 12 D)/T³, c0 = (6 D − 2 V T)/T². The corrected acceleration is still
    // piecewise linear, so it is integrated exactly again.
    const double T = r.times.back() - r.times.front();
    const double V = r.velocity.back(), D = r.displacement.back();
    const double c1 = (6.0 * V * T - 12.0 * D) / (T * T * T);
    const double c0 = (6.0 * D - 2.0 * V * T) / (T * T);
    for (std::size_t k = 0; k < r.samples(); ++k) {
      r.acceleration[k] -= c0 + c1 * (r.times[k] - r.times.front());
    }
    integrate(r);
  }
  set_bounds(r);
  return r;
}

}  // namespace condyn
