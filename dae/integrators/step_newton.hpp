#pragma once
/// What the Newmark family's stepper (dae/integrators/newmark_stepper.hpp) asks of the Newton
/// system of one step, whichever constraint form it holds: at index 3
/// (dae/integrators/newmark_newton.hpp) or stabilized at index 2
/// (dae/integrators/stabilized_newmark_newton.hpp). Both solve for the state at t_{n+1} in
/// scaled unknowns whose first n entries are Δu, and both keep v and ü tied to the step's
/// formulas, Δv = γ' Δw and Δü = β' Δw, w the step's Newmark displacement.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>

namespace condyn {

/// β' and γ' of the step: β' = (1 − αm) / (h² β (1 − αf)), γ' = γ / (h β).
struct StepCoefficients {
  double beta_prime = 0.0, gamma_prime = 0.0;
  bool operator==(const StepCoefficients&) const = default;
};

/// One state of the step's unknowns at t_{n+1}.
struct StepState {
  Eigen::VectorXd u, v, acc, lambda;  ///< displacements, velocities, ü, λ
  /// The stabilized form's μ, one per position-level row (empty at index 3): the correction
  /// u = w + A_pᵀ μ of the positions that lets the velocity constraints hold too.
  Eigen::VectorXd mu;
};

/// Σ_j |J_ij| over J's first `columns` columns, for every row i of J: the row sensitivities of
/// StepNewton::row_sensitivities from a matrix.
[[nodiscard]] inline Eigen::VectorXd absolute_row_sums(const Eigen::SparseMatrix<double>& J,
                                                       Eigen::Index columns) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(J.rows());
  for (Eigen::Index j = 0; j < std::min(columns, J.outerSize()); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, j); it; ++it) {
      out[it.row()] += std::abs(it.value());
    }
  }
  return out;
}

class StepNewton {
 public:
  virtual ~StepNewton() = default;
  StepNewton() = default;
  StepNewton(const StepNewton&) = delete;
  StepNewton& operator=(const StepNewton&) = delete;

  /// Prepares the predictor `x` (u on the step's formulas) for Newton's iterations.
  virtual void begin_step(StepState& /*x*/) {}
  /// The scaled residual at (t, x).
  virtual void residual(double t, const StepState& x, const StepCoefficients& c,
                        Eigen::VectorXd& out) = 0;
  /// Factors the scaled matrix at (t, x); false when it is singular.
  [[nodiscard]] virtual bool factor(double t, const StepState& x, const StepCoefficients& c) = 0;
  /// rhs ← (scaled matrix)⁻¹ rhs.
  virtual void solve_in_place(Eigen::VectorXd& rhs) const = 0;
  /// x ← x + the increment d that solve_in_place returned (its first n entries are Δu).
  virtual void apply(double t, const Eigen::VectorXd& d, const StepCoefficients& c,
                     StepState& x) = 0;
  /// Newton's iterate goes back to `x`, an earlier iterate of this step (a shortened correction
  /// follows): state kept between apply() calls is set to x's.
  virtual void return_to(double /*t*/, const StepState& /*x*/) {}

  /// How much each scaled residual row can change when every Δu_j moves by 1: Σ_j |∂row/∂u_j|
  /// over the Δu columns of the scaled matrix at (t, x) (the denominator of
  /// NewmarkStepper::solve_step's backward error).
  [[nodiscard]] virtual Eigen::VectorXd row_sensitivities(double t, const StepState& x,
                                                          const StepCoefficients& c) = 0;

  /// The size of μ (0 at index 3).
  [[nodiscard]] virtual int mu_size() const { return 0; }
  [[nodiscard]] virtual long factorizations() const = 0;
  [[nodiscard]] virtual long residuals() const = 0;
  [[nodiscard]] virtual long nonzeros() const = 0;

  /// A linear model's matrix depends on the step alone. With a ratio r > 1 its factors also serve
  /// a step whose β' lies within a factor r of the factored one's (error-controlled steps change
  /// h at most steps, each change a factorization); Newton's iterations then converge on the
  /// stale factors (NewmarkStepper::solve_step). 1 (the default): equal coefficients only.
  void set_stale_ratio(double ratio) { stale_ratio_ = ratio; }
  /// Whether the last factor() kept factors made for other coefficients.
  [[nodiscard]] bool stale() const { return stale_; }
  /// The next factor() factors afresh.
  void drop_factors() { factored_ = false; }

 protected:
  /// Whether the factors held serve `c` (a linear model's, by the rule above); sets stale().
  [[nodiscard]] bool keeps_factors(bool linear, const StepCoefficients& c) {
    if (!linear || !factored_) return false;
    const double r = c.beta_prime / factored_for_.beta_prime;
    stale_ = !(c == factored_for_);
    return !stale_ || (stale_ratio_ > 1.0 && r <= stale_ratio_ && r * stale_ratio_ >= 1.0);
  }
  /// Records a factorization made for `c` (`ok`: not singular); returns `ok`.
  bool record_factors(bool ok, const StepCoefficients& c) {
    factored_ = ok;
    factored_for_ = c;
    stale_ = false;
    return ok;
  }

 private:
  bool factored_ = false, stale_ = false;
  StepCoefficients factored_for_;
  double stale_ratio_ = 1.0;
};

}  // namespace condyn
