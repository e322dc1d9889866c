// The exact decision whether a weighted sum of time functions vanishes (zero_sum.hpp).

#include "models/core/zero_sum.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace condyn {

namespace {

/// One merged coefficient: its value and the sum of the magnitudes that went into it.
struct Coefficient {
  double value = 0.0, size = 0.0;
  void add(double c, double magnitude) {
    value += c;
    size += std::abs(magnitude);
  }
  [[nodiscard]] bool is_zero() const {
    // Roundoff of the weights (a QR solve) and of cos φ, sin φ: far below 1e-9 of the terms.
    constexpr double kRoundoff = 1e-9;
    return std::abs(value) <= kRoundoff * size;
  }
};

std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

/// Keys (frequencies, rates, step times) that differ by roundoff only: undecidable.
std::string near_duplicate(const std::vector<double>& keys, const std::string& what) {
  constexpr double kNear = 1e-9;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    const double a = keys[i], b = keys[i + 1];
    if (a != b && std::abs(a - b) <= kNear * std::max(std::abs(a), std::abs(b))) {
      return what + " " + num(a) + " and " + num(b) + " differ only in the last digits";
    }
  }
  return "";
}

using HarmonicCoefficients = std::map<double, std::pair<Coefficient, Coefficient>>;

/// w ∫₀ᵗ term: a harmonic's A/ω (cos φ − cos(ωt + φ)), an exponential's A/r (exp(rt) − 1), or
/// A t sin φ and A t at zero frequency and rate, added to the coefficients of t^k, sin, cos and
/// exp.
void add_integrated(double w, const TimeTerm& term, std::map<std::size_t, Coefficient>& poly,
                    HarmonicCoefficients& harmonic, std::map<double, Coefficient>& exponential) {
  const double a = w * term.amplitude;
  if (term.kind == TimeTerm::Kind::harmonic) {
    if (term.omega == 0.0) {
      poly[1].add(a * std::sin(term.phase), a);
      return;
    }
    const double scale = a / term.omega;
    poly[0].add(scale * std::cos(term.phase), scale);
    // −cos(ωt + φ) = −cos(|ω| t + σφ) = sin(σφ) sin(|ω| t) − cos(σφ) cos(|ω| t), σ = sign ω.
    const double sign = term.omega < 0.0 ? -1.0 : 1.0;
    auto& [sc, cc] = harmonic[std::abs(term.omega)];
    sc.add(scale * std::sin(sign * term.phase), scale);
    cc.add(-scale * std::cos(sign * term.phase), scale);
    return;
  }
  if (term.rate == 0.0) {
    poly[1].add(a, a);
    return;
  }
  exponential[term.rate].add(a / term.rate, a / term.rate);
  poly[0].add(-a / term.rate, a / term.rate);
}

}  // namespace

ZeroSumVerdict weighted_sum_vanishes(const std::vector<std::pair<double, const TimeFunction*>>& sum,
                                     double t_end) {
  std::map<std::size_t, Coefficient> poly;
  HarmonicCoefficients harmonic;                    // ω -> (sin ω t, cos ω t)
  std::map<double, Coefficient> exponential, step;  // rate, start
  for (const auto& [w, f] : sum) {
    for (const auto& term : f->terms()) {
      if (term.integrated) {
        add_integrated(w, term, poly, harmonic, exponential);
        continue;
      }
      switch (term.kind) {
        case TimeTerm::Kind::polynomial:
          for (std::size_t k = 0; k < term.coefficients.size(); ++k) {
            poly[k].add(w * term.coefficients[k], w * term.coefficients[k]);
          }
          break;
        case TimeTerm::Kind::step:
          if (term.start <= 0.0) {
            poly[0].add(w * term.amplitude, w * term.amplitude);
          } else if (term.start <= t_end) {
            step[term.start].add(w * term.amplitude, w * term.amplitude);
          }
          break;
        case TimeTerm::Kind::exponential:
          if (term.rate == 0.0) {
            poly[0].add(w * term.amplitude, w * term.amplitude);
          } else {
            exponential[term.rate].add(w * term.amplitude, w * term.amplitude);
          }
          break;
        case TimeTerm::Kind::harmonic: {
          const double a = w * term.amplitude;
          if (term.omega == 0.0) {
            poly[0].add(a * std::sin(term.phase), a);
            break;
          }
          // sin(−|ω| t + φ) = −sin(|ω| t − φ)
          const double sign = term.omega < 0.0 ? -1.0 : 1.0;
          auto& [s, c] = harmonic[std::abs(term.omega)];
          s.add(a * sign * std::cos(sign * term.phase), a);
          c.add(a * sign * std::sin(sign * term.phase), a);
          break;
        }
        case TimeTerm::Kind::table:
        case TimeTerm::Kind::record:
          // Constraints refuse tables (constraint_rows.cpp); a record's samples are data, whose
          // combination is not decided from terms.
          return {ZeroSumVerdict::Kind::undecided,
                  term.describe() + " is tabulated: not decided from its terms"};
      }
    }
  }
  std::vector<double> omegas, rates, starts;
  for (const auto& [k, v] : harmonic) omegas.push_back(k);
  for (const auto& [k, v] : exponential) rates.push_back(k);
  for (const auto& [k, v] : step) starts.push_back(k);
  for (const auto& doubt :
       {near_duplicate(omegas, "the frequencies"), near_duplicate(rates, "the exponential rates"),
        near_duplicate(starts, "the step times")}) {
    if (!doubt.empty()) return {ZeroSumVerdict::Kind::undecided, doubt};
  }
  std::vector<std::string> left;
  for (const auto& [k, c] : poly) {
    if (c.is_zero()) continue;
    left.push_back(num(c.value) + (k == 0 ? "" : k == 1 ? "*t" : "*t^" + std::to_string(k)));
  }
  for (const auto& [omega, sc] : harmonic) {
    if (!sc.first.is_zero()) left.push_back(num(sc.first.value) + "*sin(" + num(omega) + "*t)");
    if (!sc.second.is_zero()) left.push_back(num(sc.second.value) + "*cos(" + num(omega) + "*t)");
  }
  for (const auto& [rate, c] : exponential) {
    if (!c.is_zero()) left.push_back(num(c.value) + "*exp(" + num(rate) + "*t)");
  }
  for (const auto& [start, c] : step) {
    if (!c.is_zero()) left.push_back(num(c.value) + "*H(t-" + num(start) + ")");
  }
  if (left.empty()) return {ZeroSumVerdict::Kind::zero, ""};
  std::string detail;
  for (const auto& l : left) detail += (detail.empty() ? "" : " + ") + l;
  return {ZeroSumVerdict::Kind::nonzero, detail};
}

}  // namespace condyn
