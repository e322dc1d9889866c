#include "models/core/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace condyn {

namespace {

/// sin(x)/x, 1 at 0 (and for x so small that sin x is x).
double sinc(double x) { return x == 0.0 ? 1.0 : std::sin(x) / x; }
/// (exp(x) − 1)/x, 1 at 0.
double expm1_ratio(double x) { return x == 0.0 ? 1.0 : std::expm1(x) / x; }

/// (sin(x + φ), cos(x + φ)) by the angle sum, never rounding x + φ: with φ = π and x = 1e-4 t the
/// sum moved in steps of ulp(π) = 4.4e-16, a staircase a slow drive of amplitude 1e4 showed at
/// 4e-12, where sin x cos φ + cos x sin φ is a few ulps of the value.
std::pair<double, double> sin_cos_sum(double x, double phase) {
  if (phase == 0.0) return {std::sin(x), std::cos(x)};
  const double s = std::sin(x), c = std::cos(x), sp = std::sin(phase), cp = std::cos(phase);
  return {s * cp + c * sp, c * cp - s * sp};
}

double polynomial_derivative(const std::vector<double>& c, int order, double t) {
  // Horner on the differentiated coefficients: d^order/dt^order sum_k c_k t^k.
  double result = 0.0;
  for (std::size_t k = c.size(); k-- > static_cast<std::size_t>(order);) {
    double factor = 1.0;
    for (int j = 0; j < order; ++j) factor *= static_cast<double>(k - static_cast<std::size_t>(j));
    result = result * t + factor * c[k];
  }
  return result;
}

}  // namespace

double TimeTerm::derivative(int order, double t, double step_reference) const {
  if (order < 0 || order > 2)
    throw std::invalid_argument("time derivative order must be 0, 1 or 2");
  if (integrated && order == 0) {
    // ∫₀ᵗ of the plain term; its derivatives are the plain term's of one order less.
    if (kind == Kind::harmonic) {
      const double half = 0.5 * omega * t;
      return amplitude * t * sinc(half) * sin_cos_sum(half, phase).first;
    }
    return amplitude * t * expm1_ratio(rate * t);
  }
  if (integrated) return plain().derivative(order - 1, t, step_reference);
  switch (kind) {
    case Kind::step:
      return (order == 0 && start <= step_reference) ? amplitude : 0.0;
    case Kind::polynomial:
      return polynomial_derivative(coefficients, order, t);
    case Kind::harmonic: {
      const auto [sin_arg, cos_arg] = sin_cos_sum(omega * t, phase);
      switch (order) {
        case 0:
          return amplitude * sin_arg;
        case 1:
          return amplitude * omega * cos_arg;
        default:
          return -amplitude * omega * omega * sin_arg;
      }
    }
    case Kind::exponential:
      return amplitude * std::pow(rate, order) * std::exp(rate * t);
    case Kind::table:
      // Piecewise linear: the value, the segment's slope, and 0 for the second derivative.
      if (order == 0) return amplitude * table->value(t);
      // The slope as the segment that began at step_reference sees it: one-sided at a sample
      // where a stop ends the segment (Model::breakpoints stops a drive's table at its samples).
      return order == 1 ? amplitude * table->slope(t, step_reference) : 0.0;
    case Kind::record:
      return amplitude * record->derivative(order, t);
  }
  return 0.0;
}

double TimeTerm::magnitude(int order, double t) const {
  if (integrated) {
    // The integral's size |A t sinc(ωt/2)| (its sin factor may pass through 0), or |A t φ₁(rt)|;
    // its derivatives are the plain term's.
    if (order > 0) return plain().magnitude(order - 1, t);
    if (kind == Kind::harmonic) return std::abs(amplitude * t * sinc(0.5 * omega * t));
    return std::abs(derivative(0, t));
  }
  switch (kind) {
    case Kind::harmonic:
      return std::abs(amplitude) * std::pow(std::abs(omega), order);
    case Kind::polynomial: {
      // Σ |c_k| k!/(k−order)! |t|^(k−order): the derivative of |c| at |t|, every term positive.
      std::vector<double> sizes(coefficients.size());
      for (std::size_t k = 0; k < sizes.size(); ++k) sizes[k] = std::abs(coefficients[k]);
      return polynomial_derivative(sizes, order, std::abs(t));
    }
    case Kind::record:
      // Its samples' roundoff is relative to the record's size: a velocity recorded as 1e-17
      // where it is 0 (sin π) is zero against a peak of 0.06.
      return std::abs(amplitude) * record->bound[static_cast<std::size_t>(order)];
    default:
      return std::abs(derivative(order, t));
  }
}

TimeTerm TimeTerm::derivative_term() const {
  if (integrated) return plain();  // d/dt ∫₀ᵗ f = f
  TimeTerm d = *this;
  switch (kind) {
    case Kind::step:
      d = TimeTerm{};
      break;
    case Kind::polynomial:
      d.coefficients.clear();
      for (std::size_t k = 1; k < coefficients.size(); ++k) {
        d.coefficients.push_back(static_cast<double>(k) * coefficients[k]);
      }
      break;
    case Kind::harmonic:
      d.amplitude = amplitude * omega;
      d.phase = phase + std::numbers::pi / 2;
      break;
    case Kind::exponential:
      d.amplitude = amplitude * rate;
      break;
    case Kind::table:
      throw std::invalid_argument("the derivative of " + describe() +
                                  " is piecewise constant: no time-function term represents it");
    case Kind::record:
      throw std::invalid_argument("the derivative of " + describe() +
                                  " is piecewise polynomial: no time-function term represents it");
  }
  return d;
}

bool TimeTerm::is_zero() const {
  switch (kind) {
    case Kind::polynomial:
      for (double c : coefficients) {
        if (c != 0.0) return false;
      }
      return true;
    case Kind::harmonic:  // integrated or not: zero with its integrand
      return amplitude == 0.0 || (omega == 0.0 && std::sin(phase) == 0.0);
    case Kind::table:
      return amplitude == 0.0 || table->max_abs_value == 0.0;
    case Kind::record:
      return amplitude == 0.0 || record->bound[0] == 0.0;
    default:
      return amplitude == 0.0;
  }
}

TimeTerm TimeTerm::plain() const {
  TimeTerm p = *this;
  p.integrated = false;
  return p;
}

std::string TimeTerm::describe() const {
  std::ostringstream s;
  s.precision(6);
  switch (kind) {
    case Kind::step:
      s << amplitude << "*H(t" << (start < 0 ? "+" : "-") << std::abs(start) << ")";
      break;
    case Kind::polynomial: {
      bool first = true;
      for (std::size_t k = 0; k < coefficients.size(); ++k) {
        if (coefficients[k] == 0.0) continue;
        if (!first) s << (coefficients[k] < 0 ? " - " : " + ");
        const double c = first ? coefficients[k] : std::abs(coefficients[k]);
        s << c;
        if (k >= 1) s << "*t";
        if (k >= 2) s << "^" << k;
        first = false;
      }
      if (first) s << "0";
      break;
    }
    case Kind::harmonic: {
      const char* x = integrated ? "*s" : "*t";
      s << amplitude << (integrated ? "*int_0^t sin(" : "*sin(") << omega << x
        << (phase < 0 ? "-" : "+") << std::abs(phase) << ")" << (integrated ? " ds" : "");
      break;
    }
    case Kind::exponential:
      s << amplitude << (integrated ? "*int_0^t exp(" : "*exp(") << rate
        << (integrated ? "*s) ds" : "*t)");
      break;
    case Kind::table:
      s << "table(" << table->file << ":" << table->column << ", " << table->samples()
        << " samples)";
      if (amplitude != 1.0) s << "*" << amplitude;
      break;
    case Kind::record:
      s << "record(" << record->source << ", " << record->samples() << " samples)";
      if (amplitude != 1.0) s << "*" << amplitude;
      break;
  }
  return s.str();
}

TimeFunction TimeFunction::scaled(double c) const {
  if (c == 0.0) return {};
  std::vector<TimeTerm> out = terms_;
  for (auto& term : out) {
    switch (term.kind) {
      case TimeTerm::Kind::polynomial:
        for (double& a : term.coefficients) a *= c;
        break;
      case TimeTerm::Kind::step:
      case TimeTerm::Kind::harmonic:
      case TimeTerm::Kind::exponential:
      case TimeTerm::Kind::table:
      case TimeTerm::Kind::record:
        term.amplitude *= c;
        break;
    }
  }
  return TimeFunction(std::move(out));
}

TimeFunction TimeFunction::constant(double c) {
  TimeTerm term;
  term.kind = TimeTerm::Kind::polynomial;
  term.coefficients = {c};
  return TimeFunction({term});
}

double TimeFunction::derivative(int order, double t, double step_reference) const {
  double sum = 0.0;
  for (const auto& term : terms_) sum += term.derivative(order, t, step_reference);
  return sum;
}

double TimeFunction::magnitude(int order, double t) const {
  double sum = 0.0;
  for (const auto& term : terms_) sum += term.magnitude(order, t);
  return sum;
}

bool TimeFunction::is_zero() const {
  for (const auto& term : terms_) {
    if (!term.is_zero()) return false;
  }
  return true;
}

bool TimeFunction::is_constant() const {
  for (const auto& term : terms_) {
    if (term.is_zero()) continue;
    switch (term.kind) {
      case TimeTerm::Kind::step:
        if (term.start > 0.0) return false;
        break;
      case TimeTerm::Kind::polynomial:
        for (std::size_t k = 1; k < term.coefficients.size(); ++k) {
          if (term.coefficients[k] != 0.0) return false;
        }
        break;
      case TimeTerm::Kind::harmonic:  // integrated and nonzero: grows with t
        if (term.omega != 0.0 || term.integrated) return false;
        break;
      case TimeTerm::Kind::exponential:
        if (term.rate != 0.0 || term.integrated) return false;
        break;
      case TimeTerm::Kind::table:
        if (term.table->max_abs_slope != 0.0) return false;
        break;
      case TimeTerm::Kind::record:
        if (term.record->bound[1] != 0.0 || term.record->bound[2] != 0.0) return false;
        break;
    }
  }
  return true;
}

bool TimeFunction::has_table() const {
  return std::any_of(terms_.begin(), terms_.end(),
                     [](const TimeTerm& term) { return term.kind == TimeTerm::Kind::table; });
}

bool TimeFunction::has_record() const {
  return std::any_of(terms_.begin(), terms_.end(),
                     [](const TimeTerm& term) { return term.kind == TimeTerm::Kind::record; });
}

std::vector<double> TimeFunction::breakpoints() const {
  std::vector<double> times;
  for (const auto& term : terms_) {
    if (term.kind == TimeTerm::Kind::step && term.start > 0.0 && term.amplitude != 0.0) {
      times.push_back(term.start);
    }
  }
  return times;
}

TimeFunction TimeFunction::acting_until(double t_end, std::vector<double>& dropped) const {
  std::vector<TimeTerm> kept;
  for (const auto& term : terms_) {
    if (term.kind == TimeTerm::Kind::step && term.start > t_end) {
      dropped.push_back(term.start);
    } else {
      kept.push_back(term);
    }
  }
  return TimeFunction(std::move(kept));
}

std::vector<double> TimeFunction::kinks() const {
  std::vector<double> out;
  for (const auto& term : terms_) {
    if (term.kind == TimeTerm::Kind::table && term.table && term.amplitude != 0.0)
      out.insert(out.end(), term.table->times.begin(), term.table->times.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double TimeFunction::first_kink_after(double t) const {
  double first = std::numeric_limits<double>::infinity();
  for (const auto& term : terms_) {
    if (term.kind != TimeTerm::Kind::table || !term.table) continue;
    const auto& times = term.table->times;
    const auto after = std::upper_bound(times.begin(), times.end(), t);
    if (after != times.end()) first = std::min(first, *after);
  }
  return first;
}

TimeFunction TimeFunction::antiderivative() const {
  std::vector<TimeTerm> out;
  // Constant of integration chosen so that F(0) = 0; collected in one polynomial term.
  TimeTerm poly;
  poly.kind = TimeTerm::Kind::polynomial;
  poly.coefficients = {0.0, 0.0};
  auto add_poly = [&](std::size_t k, double c) {
    if (poly.coefficients.size() <= k) poly.coefficients.resize(k + 1, 0.0);
    poly.coefficients[k] += c;
  };
  for (const auto& term : terms_) {
    if (term.is_zero()) continue;
    if (term.integrated) {
      throw std::invalid_argument(term.describe() + " is an antiderivative: not integrated again");
    }
    switch (term.kind) {
      case TimeTerm::Kind::step:
        if (term.start > 0.0) {
          throw std::invalid_argument("a step at t = " + std::to_string(term.start) +
                                      " > 0 integrates to a ramp whose derivative jumps");
        }
        add_poly(1, term.amplitude);
        break;
      case TimeTerm::Kind::polynomial:
        for (std::size_t k = 0; k < term.coefficients.size(); ++k) {
          add_poly(k + 1, term.coefficients[k] / static_cast<double>(k + 1));
        }
        break;
      case TimeTerm::Kind::harmonic:
        if (term.omega == 0.0) {
          add_poly(1, term.amplitude * std::sin(term.phase));
        } else {
          // One integrated term, its phase as written: as A/ω (cos φ − cos(ωt + φ)) a small ωt
          // cancels, and a phase shifted by π/2 is rounded (sin(ωt/2 + φ − π/2) near a zero).
          TimeTerm h = term;
          h.integrated = true;
          out.push_back(h);
        }
        break;
      case TimeTerm::Kind::exponential:
        if (term.rate == 0.0) {
          add_poly(1, term.amplitude);
        } else {
          TimeTerm e = term;  // ∫₀ᵗ A exp(rs) ds = A t expm1(rt)/(rt)
          e.integrated = true;
          out.push_back(e);
        }
        break;
      case TimeTerm::Kind::table:
      case TimeTerm::Kind::record:
        throw std::invalid_argument(term.describe() +
                                    " is not integrated (a table is a load, a record a prescribed "
                                    "displacement: neither is a prescribed velocity)");
    }
  }
  out.push_back(poly);
  return TimeFunction(std::move(out));
}

std::string TimeFunction::describe() const {
  std::string s;
  for (const auto& term : terms_) {
    if (term.is_zero()) continue;
    if (!s.empty()) s += " + ";
    s += term.describe();
  }
  return s.empty() ? "0" : s;
}

}  // namespace condyn
