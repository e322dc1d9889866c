#pragma once
/// Exact solution of a linear time-invariant second-order system by modal superposition:
///
///   M q'' + C q' + K q = sum_j b_j tau_j(t),   q(0) = q0,  q'(0) = v0,
///
/// with M symmetric positive definite, K symmetric positive semi-definite (zero-frequency modes
/// allowed), C classical (diagonal in the M-orthonormal modes of (K, M); C = 0 included), and each
/// tau_j a single TimeTerm (step, polynomial, harmonic, exponential, table). Each modal coordinate
/// obeys x'' + c x' + k x = p(t), i.e. (D - s1)(D - s2) x = p with s1,2 the roots of s^2 + c s + k.
/// Its response is expressed through divided differences of z -> exp(z t) over the roots and the
/// forcing exponents (t^k/k! <-> k+1 zeros, exp(r t) <-> r, sin <-> +-i omega, a step at t0 <->
/// one zero in the shifted time t - t0). The divided differences are evaluated by Opitz' formula
/// (the exponential of a bidiagonal matrix), which stays exact when points coincide: zero-frequency
/// modes, critical damping and resonance need no special case. A table (piecewise linear) is exact
/// piece by piece: the state at each sample is carried to the next by the free response plus the
/// response to the piece's constant and ramp (the classical recurrence for piecewise linear
/// excitation, Nigam and Jennings 1969), computed once per mode; at(t) then starts from the last
/// sample before t (binary search).

#include <Eigen/Dense>
#include <complex>
#include <memory>
#include <stdexcept>
#include <vector>

#include "models/core/time_function.hpp"

namespace condyn {

/// Raised when the system has no closed-form modal solution here (M not positive definite,
/// non-classical damping, ...). The message says which condition failed and by how much.
class ExactSolutionUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One forcing term b * tau(t); b has the size of q.
struct LtiForcing {
  Eigen::VectorXd b;
  TimeTerm term;
};

/// The system M q'' + C q' + K q = sum_j b_j tau_j(t). C may be an empty (0x0) matrix: no damping.
struct LtiSystem {
  Eigen::MatrixXd M, C, K;
  std::vector<LtiForcing> forcing;
  Eigen::VectorXd q0, v0;
};

/// q, q' and q'' at one time.
struct LtiState {
  Eigen::VectorXd q, v, a;
};

struct StaticCondensation;

class ModalSolution {
 public:
  /// Decomposes the system. A singular M whose null space stiffness holds and no damping acts on
  /// is condensed statically first (validation/references/static_condensation.hpp). Throws
  /// ExactSolutionUnavailable when M is not symmetric positive (semi-)definite, K is not
  /// symmetric, C is not diagonal in the modal basis (relative off-diagonal size above 1e-9), or
  /// the condensation does not apply, and std::invalid_argument on inconsistent sizes.
  explicit ModalSolution(const LtiSystem& system);

  /// The exact state at time t >= 0. Steps are on for t >= start (H(0) = 1), so q'' at a step
  /// time is the right limit.
  [[nodiscard]] LtiState at(double t) const;

  /// Undamped natural frequencies sqrt(k_i) in rad/s, ascending (zero-frequency modes give 0);
  /// those of the condensed system when M is singular.
  [[nodiscard]] const Eigen::VectorXd& natural_frequencies() const { return omega_; }

 private:
  /// Set when M was singular: the condensation and the solution of the reduced system, which
  /// at() expands; the members below are then unused.
  std::shared_ptr<const StaticCondensation> condensation_;
  std::shared_ptr<const ModalSolution> reduced_;

  /// Fills knots_, knot_x_, knot_v_ for the table terms.
  void carry_tables();

  Eigen::MatrixXd phi_;       ///< M-orthonormal modes, columns
  Eigen::VectorXd omega_;     ///< sqrt of modal stiffness (clamped at 0)
  Eigen::VectorXd k_, c_;     ///< modal stiffness and damping
  Eigen::VectorXd x0_, xd0_;  ///< modal initial conditions
  std::vector<TimeTerm> terms_;
  Eigen::MatrixXd p_;  ///< modal load amplitudes: p_(i, j) = phi_i^T b_j
  /// Table terms j: knot times (0, then the samples after 0) and each mode's response to the term
  /// alone (unit modal load) at them, x in knot_x_[j](mode, knot), x' in knot_v_[j]; empty for
  /// other terms.
  std::vector<std::vector<double>> knots_;
  std::vector<Eigen::MatrixXd> knot_x_, knot_v_;
};

/// Divided difference exp(z t)[z_0, ..., z_n] and its first two time derivatives
/// (z exp(z t)[...], z^2 exp(z t)[...]), by Opitz' formula. Points may coincide. Exposed for tests.
struct DividedDifference {
  std::complex<double> value, d1, d2;
};
[[nodiscard]] DividedDifference exp_divided_difference(const std::vector<std::complex<double>>& z,
                                                       double t);

}  // namespace condyn
