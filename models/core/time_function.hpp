#pragma once
/// Scalar functions of time used for loads and constraint right-hand sides (scene-format.md,
/// "Time functions"): sums of step, polynomial, harmonic and exponential terms, each with exact
/// first and second derivatives, and tables read from CSV files ("Time functions from data";
/// models/core/time_table.hpp), piecewise linear: their first derivative is the segment's slope,
/// their second is taken as 0, so they serve loads, not position-level right-hand sides; and
/// displacement records (models/core/kinematic_record.hpp), twice continuously differentiable,
/// which serve as a prescribed displacement.

#include <memory>
#include <string>
#include <vector>

#include "models/core/kinematic_record.hpp"
#include "models/core/time_table.hpp"

namespace condyn {

/// One term of a time function.
struct TimeTerm {
  enum class Kind { step, polynomial, harmonic, exponential, table, record };
  Kind kind = Kind::polynomial;
  double amplitude = 1.0;            ///< step, harmonic, exponential; table, record: its `scale`
  double start = 0.0;                ///< step: amplitude * H(t - start), H(0) = 1
  std::vector<double> coefficients;  ///< polynomial: sum_k c_k t^k
  double omega = 0.0;                ///< harmonic: amplitude * sin(omega t + phase)
  double phase = 0.0;
  double rate = 0.0;  ///< exponential: amplitude * exp(rate t)
  /// harmonic, exponential: the term is the integral from 0 to t of the term without this flag,
  /// the form of an antiderivative, evaluated without cancellation and without dividing by ω or r:
  /// ∫₀ᵗ A sin(ωs + φ) ds = A t sinc(ωt/2) sin(ωt/2 + φ) and ∫₀ᵗ A exp(rs) ds = A t expm1(rt)/(rt).
  /// Written as A/ω (cos φ − cos(ωt + φ)), ∫₀ᵗ sin(10⁻¹² s) ds is the difference of two numbers of
  /// 10¹² and keeps 4 digits; ω = 1e-310 overflows A/ω. Never set from a scene.
  bool integrated = false;
  /// table: amplitude * f(t) of the samples (piecewise linear); shared and immutable, so copies
  /// of the term (loads, scaled patterns) cost a pointer.
  std::shared_ptr<const TimeTable> table;
  /// record: amplitude * the record's displacement (quintic Hermite between samples); shared.
  std::shared_ptr<const KinematicRecord> record;

  /// d^order/dt^order of the term at t, order in {0, 1, 2}. A step contributes to order 0 only
  /// (its derivative is an impulse at `start`, which callers handle as a discontinuity).
  /// `step_reference` decides which steps are on: a step is on when start <= step_reference.
  /// Callers integrating across a step pass the start of the current segment so that the
  /// residual never sees a step switch on inside the segment; plain evaluation passes t.
  [[nodiscard]] double derivative(int order, double t, double step_reference) const;
  [[nodiscard]] double derivative(int order, double t) const { return derivative(order, t, t); }
  [[nodiscard]] double value(double t) const { return derivative(0, t, t); }
  /// The size against which derivative(order, t)'s roundoff is judged: |amplitude| ω^order for a
  /// harmonic (whatever the phase: at sin(π) the value is roundoff of the amplitude), the sum of
  /// the polynomial's terms' sizes, a record's peak (its bound), else |derivative(order, t)|.
  [[nodiscard]] double magnitude(int order, double t) const;

  /// The term whose value is this term's first derivative (smooth kinds only; a step gives an
  /// all-zero polynomial). Throws std::invalid_argument for a table (its slope is piecewise
  /// constant: no term represents it) and a record (its velocity is no term either).
  [[nodiscard]] TimeTerm derivative_term() const;
  /// True when the term is identically zero for t >= 0.
  [[nodiscard]] bool is_zero() const;
  /// The term without `integrated`: the integrand of an integrated term.
  [[nodiscard]] TimeTerm plain() const;
  /// Human-readable form, e.g. "2*H(t-1)", "3*sin(2*t+0.5)" or
  /// "table(el_centro.csv:acceleration_g, 1559 samples)*9.81".
  [[nodiscard]] std::string describe() const;
};

/// A sum of terms; the empty sum is the zero function.
class TimeFunction {
 public:
  TimeFunction() = default;
  explicit TimeFunction(std::vector<TimeTerm> terms) : terms_(std::move(terms)) {}
  static TimeFunction constant(double c);

  [[nodiscard]] const std::vector<TimeTerm>& terms() const { return terms_; }
  [[nodiscard]] double derivative(int order, double t, double step_reference) const;
  [[nodiscard]] double derivative(int order, double t) const { return derivative(order, t, t); }
  [[nodiscard]] double value(double t) const { return derivative(0, t, t); }

  /// Σ of the terms' magnitude(order, t): the size of derivative(order, t)'s summands, so that
  /// a sum that cancels (0.1 + 0.2 − 0.3) or a harmonic at a zero (sin(π)) is judged against its
  /// parts, not against its roundoff.
  [[nodiscard]] double magnitude(int order, double t) const;
  /// True when every term is zero for t >= 0 (a homogeneous right-hand side).
  [[nodiscard]] bool is_zero() const;
  /// True when the function is constant for t >= 0: no time dependence (scleronomic). A table is
  /// constant when all its values are equal.
  [[nodiscard]] bool is_constant() const;
  /// True when a term is a table (piecewise linear: no exact second derivative).
  [[nodiscard]] bool has_table() const;
  /// True when a term is a displacement record (a prescribed displacement, not a load).
  [[nodiscard]] bool has_record() const;
  /// Times t > 0 where a step switches on: the integrator stops and restarts there. A table's
  /// samples are not breakpoints of a load: its kinks are continuous in value, and the
  /// integrator's error control resolves them (docs/scenes.md, "Tabulated time functions"); a
  /// drive's are (kinks()).
  [[nodiscard]] std::vector<double> breakpoints() const;
  /// The sample times of its table terms, ascending, where its first derivative jumps: a drive
  /// prescribes a velocity that jumps there (Model::breakpoints).
  [[nodiscard]] std::vector<double> kinks() const;
  /// The function as it acts on [0, t_end]: steps that switch on after t_end left out (a run
  /// never reaches them). `dropped` receives their start times.
  [[nodiscard]] TimeFunction acting_until(double t_end, std::vector<double>& dropped) const;
  /// The first sample time of a table term after t (infinity when none): the integrator's first
  /// step stays short of it (Model::first_kink).
  [[nodiscard]] double first_kink_after(double t) const;
  /// The antiderivative F(t) = integral_0^t f, itself a sum of supported terms.
  /// Throws std::invalid_argument when a step starts after t = 0 (its integral is a ramp,
  /// whose derivative jumps: the caller must refuse the constraint), and for a table or a record
  /// (refused as a velocity constraint's right-hand side), and for an antiderivative's own terms
  /// (TimeTerm::integrated: no caller integrates twice).
  [[nodiscard]] TimeFunction antiderivative() const;
  [[nodiscard]] std::string describe() const;
  /// c f(t): every term's amplitude (a polynomial's coefficients, a table's scale) times c; c = 0
  /// gives the zero function (a load pattern's or a constraint block's entry times its time
  /// function).
  [[nodiscard]] TimeFunction scaled(double c) const;

 private:
  std::vector<TimeTerm> terms_;
};

}  // namespace condyn
