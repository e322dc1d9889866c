#include "models/time_function.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace condyn {

namespace {

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
  switch (kind) {
    case Kind::step:
      return (order == 0 && start <= step_reference) ? amplitude : 0.0;
    case Kind::polynomial:
      return polynomial_derivative(coefficients, order, t);
    case Kind::harmonic: {
      const double arg = omega * t + phase;
      switch (order) {
        case 0:
          return amplitude * std::sin(arg);
        case 1:
          return amplitude * omega * std::cos(arg);
        default:
          return -amplitude * omega * omega * std::sin(arg);
      }
    }
    case Kind::exponential:
      return amplitude * std::pow(rate, order) * std::exp(rate * t);
  }
  return 0.0;
}

TimeTerm TimeTerm::derivative_term() const {
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
    case Kind::harmonic:
      return amplitude == 0.0 || (omega == 0.0 && std::sin(phase) == 0.0);
    default:
      return amplitude == 0.0;
  }
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
    case Kind::harmonic:
      s << amplitude << "*sin(" << omega << "*t" << (phase < 0 ? "-" : "+") << std::abs(phase)
        << ")";
      break;
    case Kind::exponential:
      s << amplitude << "*exp(" << rate << "*t)";
      break;
  }
  return s.str();
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
      case TimeTerm::Kind::harmonic:
        if (term.omega != 0.0) return false;
        break;
      case TimeTerm::Kind::exponential:
        if (term.rate != 0.0) return false;
        break;
    }
  }
  return true;
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
          // integral of A sin(w t + p) = -A/w cos(w t + p) + A/w cos p = A/w sin(w t + p - pi/2) +
          // ...
          TimeTerm h = term;
          h.amplitude = term.amplitude / term.omega;
          h.phase = term.phase - std::numbers::pi / 2;
          out.push_back(h);
          add_poly(0, term.amplitude / term.omega * std::cos(term.phase));
        }
        break;
      case TimeTerm::Kind::exponential:
        if (term.rate == 0.0) {
          add_poly(1, term.amplitude);
        } else {
          TimeTerm e = term;
          e.amplitude = term.amplitude / term.rate;
          out.push_back(e);
          add_poly(0, -term.amplitude / term.rate);
        }
        break;
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
