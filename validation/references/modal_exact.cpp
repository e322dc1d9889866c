#include "validation/references/modal_exact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <utility>

#include "models/core/eigen_decompositions.hpp"
#include "validation/references/static_condensation.hpp"

namespace condyn {

namespace {

using Complex = std::complex<double>;

// Asymmetry below this fraction of the largest entry is rounding of a symmetric matrix.
constexpr double kSymmetryTolerance = 1e-12;
// A modal stiffness within this fraction of the largest |k| is a rounded zero-frequency mode.
constexpr double kZeroStiffnessTolerance = 1e-12;
// Modal stiffnesses closer than this fraction of the largest |k| are one repeated eigenvalue.
constexpr double kRepeatedStiffnessTolerance = 1e-12;
// Modal damping coupling below this fraction of the largest modal damping is rounding.
constexpr double kDampingCouplingTolerance = 1e-9;
// A mass matrix with reciprocal condition number below this is singular to working precision.
constexpr double kMassConditionTolerance = std::numeric_limits<double>::epsilon();

std::string to_text(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

void require_finite(const Eigen::MatrixXd& a, const std::string& name) {
  if (!a.allFinite()) throw std::invalid_argument(name + " has non-finite entries");
}

void require_symmetric(const Eigen::MatrixXd& a, const std::string& name) {
  if (a.size() == 0) return;
  const double scale = a.cwiseAbs().maxCoeff();
  const double asymmetry = (a - a.transpose()).cwiseAbs().maxCoeff();
  if (asymmetry > kSymmetryTolerance * scale) {
    throw ExactSolutionUnavailable(
        name + " is not symmetric: max |A - A^T| = " + to_text(asymmetry) + ", ratio " +
        to_text(asymmetry / scale) + " to the largest entry (tolerance " +
        to_text(kSymmetryTolerance) + ")");
  }
}

void require_size(const Eigen::MatrixXd& a, Eigen::Index rows, Eigen::Index cols,
                  const std::string& name) {
  if (a.rows() != rows || a.cols() != cols) {
    throw std::invalid_argument(name + " is " + std::to_string(a.rows()) + "x" +
                                std::to_string(a.cols()) + ", expected " + std::to_string(rows) +
                                "x" + std::to_string(cols));
  }
}

/// Column n of exp(tZ), Z exp(tZ) and Z^2 exp(tZ) for the bidiagonal Z of Opitz' formula:
/// entry i is the divided difference over z_i, ..., z_n (and its time derivatives), so one
/// exponential serves every tail of the point list.
struct DividedDifferenceColumn {
  Eigen::VectorXcd value, d1, d2;

  [[nodiscard]] DividedDifference row(Eigen::Index i) const { return {value(i), d1(i), d2(i)}; }
};

DividedDifferenceColumn exp_divided_difference_column(const std::vector<Complex>& z, double t) {
  if (z.empty()) throw std::invalid_argument("divided difference over no points");
  const auto size = static_cast<Eigen::Index>(z.size());
  const Eigen::Index n = size - 1;
  DividedDifferenceColumn column;
  if (t == 0.0) {
    column.value = Eigen::VectorXcd::Unit(size, n);
  } else {
    Eigen::MatrixXcd tz = Eigen::MatrixXcd::Zero(size, size);
    for (Eigen::Index i = 0; i < size; ++i) {
      tz(i, i) = t * z[static_cast<std::size_t>(i)];
      if (i < n) tz(i, i + 1) = t;
    }
    const Eigen::MatrixXcd f = tz.exp();
    column.value = f.col(n);
  }
  // d/dt exp(tZ) = Z exp(tZ); Z is bidiagonal, so the product is one pass.
  const auto times_z = [&](const Eigen::VectorXcd& g) {
    Eigen::VectorXcd r(size);
    for (Eigen::Index i = 0; i < size; ++i) {
      r(i) = z[static_cast<std::size_t>(i)] * g(i) + (i < n ? g(i + 1) : Complex(0.0));
    }
    return r;
  };
  column.d1 = times_z(column.value);
  column.d2 = times_z(column.d1);
  return column;
}

/// A modal coordinate and its first two time derivatives.
struct Motion {
  double x = 0.0, v = 0.0, a = 0.0;

  Motion& operator+=(const Motion& o) {
    x += o.x;
    v += o.v;
    a += o.a;
    return *this;
  }
};

Motion operator*(double s, const Motion& m) { return {s * m.x, s * m.v, s * m.a}; }

// The modal equation has real coefficients, so complex parts of its responses are rounding noise
// (or, for the harmonic trick, the response to the cosine partner).
Motion real_part(const DividedDifference& d) { return {d.value.real(), d.d1.real(), d.d2.real()}; }
Motion imag_part(const DividedDifference& d) { return {d.value.imag(), d.d1.imag(), d.d2.imag()}; }

DividedDifference operator*(Complex s, const DividedDifference& d) {
  return {s * d.value, s * d.d1, s * d.d2};
}

/// Roots of s^2 + c s + k without cancellation: the real pair takes the larger root from the
/// quadratic formula and the smaller from s1 s2 = k, so s1 + s2 = -c and s1 s2 = k hold to
/// rounding even when damping is nearly critical.
std::pair<Complex, Complex> characteristic_roots(double c, double k) {
  const double half = 0.5 * c;
  const double discriminant = half * half - k;
  if (discriminant < 0.0) {
    const double omega_d = std::sqrt(-discriminant);
    return {Complex(-half, omega_d), Complex(-half, -omega_d)};
  }
  const double large = -(half + std::copysign(std::sqrt(discriminant), half));
  const double small = large != 0.0 ? k / large : 0.0;
  return {Complex(large), Complex(small)};
}

/// Zero-initial-condition response of (D - s1)(D - s2) x = term(t).
Motion forced_response(const TimeTerm& term, Complex s1, Complex s2, double t) {
  switch (term.kind) {
    case TimeTerm::Kind::step: {
      // A step starting before t = 0 is already on at t = 0: it acts from there.
      const double on = std::max(term.start, 0.0);
      if (t < on) return {};
      const auto column = exp_divided_difference_column({0.0, s1, s2}, t - on);
      return term.amplitude * real_part(column.row(0));
    }
    case TimeTerm::Kind::polynomial: {
      if (term.coefficients.empty()) return {};
      // Points {0 x (degree+1), s1, s2}; the tail starting at index degree - k holds k+1 zeros,
      // whose divided difference is the response to t^k / k!.
      const std::size_t degree = term.coefficients.size() - 1;
      std::vector<Complex> z(degree + 1, Complex(0.0));
      z.push_back(s1);
      z.push_back(s2);
      const auto column = exp_divided_difference_column(z, t);
      Motion m;
      double factorial = 1.0;
      for (std::size_t k = 0; k <= degree; ++k) {
        if (k > 0) factorial *= static_cast<double>(k);
        const double c = term.coefficients[k];
        if (c == 0.0) continue;
        m += (c * factorial) * real_part(column.row(static_cast<Eigen::Index>(degree - k)));
      }
      return m;
    }
    case TimeTerm::Kind::harmonic: {
      // sin(w t + phi) = Im(e^{i phi} e^{i w t}); real coefficients let Im pass through the
      // equation. Integrated (∫₀ᵗ e^{iws} ds = e^{t·}[0, iw]), the response is e^{t·}[0, iw, s1,
      // s2]: exact for any w, with no cancellation of terms of size 1/w.
      const auto column =
          term.integrated
              ? exp_divided_difference_column({0.0, Complex(0.0, term.omega), s1, s2}, t)
              : exp_divided_difference_column({Complex(0.0, term.omega), s1, s2}, t);
      const Complex rotation = std::polar(1.0, term.phase);
      return term.amplitude * imag_part(rotation * column.row(0));
    }
    case TimeTerm::Kind::exponential: {
      const auto column = term.integrated
                              ? exp_divided_difference_column({0.0, Complex(term.rate), s1, s2}, t)
                              : exp_divided_difference_column({Complex(term.rate), s1, s2}, t);
      return term.amplitude * real_part(column.row(0));
    }
    case TimeTerm::Kind::table:
    case TimeTerm::Kind::record:
      // ModalSolution::at() carries tables sample by sample (table_response below); records are
      // refused before (exact_trajectory).
      throw std::invalid_argument("no closed-form modal response to " + term.describe());
  }
  return {};
}

/// Response of (D - s1)(D - s2) x = 0 with x(0) = x0, x'(0) = xd0: x0 e^{s2 t} solves it with the
/// right value, and exp(zt)[s1, s2] (zero at 0, unit slope) corrects the slope.
Motion free_response(double x0, double xd0, Complex s1, Complex s2, double t) {
  if (x0 == 0.0 && xd0 == 0.0) return {};
  const auto column = exp_divided_difference_column({s1, s2}, t);
  DividedDifference x = Complex(x0) * column.row(1);
  const DividedDifference correction = (xd0 - s2 * x0) * column.row(0);
  x.value += correction.value;
  x.d1 += correction.d1;
  x.d2 += correction.d2;
  return real_part(x);
}

/// Response of (D - s1)(D - s2) x = c0 + c1 tau over tau = t - t0 >= 0 from the state (x0, xd0)
/// at t0: one piece of a piecewise linear load.
Motion piece_response(double x0, double xd0, double c0, double c1, Complex s1, Complex s2,
                      double tau) {
  TimeTerm piece;
  piece.coefficients = {c0, c1};
  Motion m = free_response(x0, xd0, s1, s2, tau);
  m += forced_response(piece, s1, s2, tau);
  return m;
}

/// The table term's response at t, from the last knot at or before t.
Motion table_response(const TimeTerm& term, const std::vector<double>& knots,
                      const Eigen::MatrixXd& knot_x, const Eigen::MatrixXd& knot_v,
                      Eigen::Index mode, Complex s1, Complex s2, double t) {
  const auto k =
      static_cast<Eigen::Index>(std::upper_bound(knots.begin(), knots.end(), t) - knots.begin()) -
      1;
  const double t0 = knots[static_cast<std::size_t>(k)];
  return piece_response(knot_x(mode, k), knot_v(mode, k), term.derivative(0, t0),
                        term.derivative(1, t0), s1, s2, t - t0);
}

/// Refuses a system whose matrices and vectors are of the wrong size, not finite or (M, K, C) not
/// symmetric, naming the part; empty C, q0 and v0 mean none and rest.
void check_system(const LtiSystem& system) {
  const Eigen::Index n = system.M.rows();
  if (n == 0) throw std::invalid_argument("the system has no coordinates (M is empty)");
  require_size(system.M, n, n, "mass matrix M");
  require_size(system.K, n, n, "stiffness matrix K");
  if (system.C.size() != 0) require_size(system.C, n, n, "damping matrix C");
  // Empty initial conditions mean rest.
  if (system.q0.size() != 0) require_size(system.q0, n, 1, "initial position q0");
  if (system.v0.size() != 0) require_size(system.v0, n, 1, "initial velocity v0");
  for (std::size_t j = 0; j < system.forcing.size(); ++j) {
    require_size(system.forcing[j].b, n, 1, "load vector b_" + std::to_string(j));
    require_finite(system.forcing[j].b, "load vector b_" + std::to_string(j));
  }
  require_finite(system.M, "mass matrix M");
  require_finite(system.K, "stiffness matrix K");
  require_finite(system.C, "damping matrix C");
  require_finite(system.q0, "initial position q0");
  require_finite(system.v0, "initial velocity v0");

  require_symmetric(system.M, "mass matrix M");
  require_symmetric(system.K, "stiffness matrix K");
  require_symmetric(system.C, "damping matrix C");
}

/// Throws ExactSolutionUnavailable unless M is positive definite to working precision.
void require_positive_mass(const Eigen::MatrixXd& M) {
  const Eigen::LLT<Eigen::MatrixXd> mass_factor(M);
  if (mass_factor.info() != Eigen::Success) {
    throw ExactSolutionUnavailable("mass matrix is not positive definite (Cholesky failed)");
  }
  const double mass_rcond = mass_factor.rcond();
  if (mass_rcond < kMassConditionTolerance) {
    throw ExactSolutionUnavailable(
        "mass matrix is not positive definite to working precision: reciprocal condition "
        "number " +
        to_text(mass_rcond));
  }
}

/// Modal stiffnesses `k` within roundoff of 0 (relative to `k_scale`, the largest |k|) set to 0;
/// throws ExactSolutionUnavailable for a negative one (K not positive semi-definite).
void clamp_modal_stiffness(Eigen::VectorXd& k, double k_scale) {
  for (Eigen::Index i = 0; i < k.size(); ++i) {
    if (std::abs(k(i)) <= kZeroStiffnessTolerance * k_scale) {
      k(i) = 0.0;
    } else if (k(i) < 0.0) {
      throw ExactSolutionUnavailable(
          "stiffness matrix is not positive semi-definite: modal stiffness " + to_text(k(i)) +
          ", ratio " + to_text(k(i) / k_scale) + " to the largest |k|");
    }
  }
}

/// The modal damping of C in the modes `phi` (of stiffnesses `k`, largest |k| `k_scale`): its
/// diagonal, after rotating each block of repeated stiffness onto its eigenvectors. Throws
/// ExactSolutionUnavailable when C couples the modes (damping not classical).
Eigen::VectorXd modal_damping(Eigen::MatrixXd& phi, const Eigen::VectorXd& k, double k_scale,
                              const Eigen::MatrixXd& C) {
  const Eigen::Index n = k.size();
  // Within a repeated eigenvalue any orthonormal basis is modal, and the solver's choice need
  // not diagonalize C even when C is classical (e.g. dashpots on a free body, K = 0). Rotating
  // each such block onto the eigenvectors of its modal damping removes that false coupling.
  Eigen::MatrixXd modal_c = phi.transpose() * C * phi;
  for (Eigen::Index begin = 0; begin < n;) {
    Eigen::Index end = begin + 1;
    while (end < n && k(end) - k(end - 1) <= kRepeatedStiffnessTolerance * k_scale) ++end;
    const Eigen::Index count = end - begin;
    if (count > 1) {
      const Eigen::MatrixXd repeated = modal_c.block(begin, begin, count, count);
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> block(repeated);
      phi.middleCols(begin, count) = (phi.middleCols(begin, count) * block.eigenvectors()).eval();
    }
    begin = end;
  }
  modal_c = phi.transpose() * C * phi;

  Eigen::VectorXd diagonal = modal_c.diagonal();
  const Eigen::MatrixXd off_diagonal = modal_c - Eigen::MatrixXd(diagonal.asDiagonal());
  const double coupling = off_diagonal.cwiseAbs().maxCoeff();
  const double scale = std::max(diagonal.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  if (coupling > kDampingCouplingTolerance * scale) {
    throw ExactSolutionUnavailable(
        "damping is not classical: max off-diagonal |Phi^T C Phi| = " + to_text(coupling) +
        ", ratio " + to_text(coupling / scale) + " to the largest modal damping (tolerance " +
        to_text(kDampingCouplingTolerance) + ")");
  }
  return diagonal;
}

}  // namespace

DividedDifference exp_divided_difference(const std::vector<std::complex<double>>& z, double t) {
  return exp_divided_difference_column(z, t).row(0);
}

ModalSolution::ModalSolution(const LtiSystem& system) {
  check_system(system);
  const Eigen::Index n = system.M.rows();
  const bool damped = system.C.size() != 0;
  if (auto condensed = condense_massless(system)) {
    condensation_ = std::make_shared<const StaticCondensation>(std::move(*condensed));
    reduced_ = std::make_shared<const ModalSolution>(condensation_->reduced);
    omega_ = reduced_->omega_;
    return;
  }
  require_positive_mass(system.M);

  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(
      system.K, system.M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (modes.info() != Eigen::Success) {
    throw ExactSolutionUnavailable("generalized eigenproblem (K, M) did not converge");
  }
  phi_ = modes.eigenvectors();
  k_ = modes.eigenvalues();
  const double k_scale = k_.cwiseAbs().maxCoeff();
  clamp_modal_stiffness(k_, k_scale);
  c_ = Eigen::VectorXd::Zero(n);
  if (damped) c_ = modal_damping(phi_, k_, k_scale, system.C);
  omega_ = k_.cwiseSqrt();

  const Eigen::MatrixXd phi_t_m = phi_.transpose() * system.M;
  x0_ = system.q0.size() != 0 ? Eigen::VectorXd(phi_t_m * system.q0) : Eigen::VectorXd::Zero(n);
  xd0_ = system.v0.size() != 0 ? Eigen::VectorXd(phi_t_m * system.v0) : Eigen::VectorXd::Zero(n);

  const auto loads = static_cast<Eigen::Index>(system.forcing.size());
  p_.resize(n, loads);
  terms_.reserve(system.forcing.size());
  for (Eigen::Index j = 0; j < loads; ++j) {
    const auto& forcing = system.forcing[static_cast<std::size_t>(j)];
    p_.col(j) = phi_.transpose() * forcing.b;
    terms_.push_back(forcing.term);
  }
  carry_tables();
}

void ModalSolution::carry_tables() {
  const Eigen::Index n = phi_.cols();
  knots_.resize(terms_.size());
  knot_x_.resize(terms_.size());
  knot_v_.resize(terms_.size());
  for (std::size_t j = 0; j < terms_.size(); ++j) {
    const TimeTerm& term = terms_[j];
    if (term.kind != TimeTerm::Kind::table) continue;
    auto& knots = knots_[j];
    knots.push_back(0.0);
    for (double tk : term.table->times) {
      if (tk > 0.0) knots.push_back(tk);
    }
    const auto count = static_cast<Eigen::Index>(knots.size());
    knot_x_[j] = Eigen::MatrixXd::Zero(n, count);  // at rest at t = 0
    knot_v_[j] = Eigen::MatrixXd::Zero(n, count);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto [s1, s2] = characteristic_roots(c_(i), k_(i));
      for (Eigen::Index k = 0; k + 1 < count; ++k) {
        const double t0 = knots[static_cast<std::size_t>(k)];
        const double t1 = knots[static_cast<std::size_t>(k + 1)];
        const Motion m = piece_response(knot_x_[j](i, k), knot_v_[j](i, k), term.derivative(0, t0),
                                        term.derivative(1, t0), s1, s2, t1 - t0);
        knot_x_[j](i, k + 1) = m.x;
        knot_v_[j](i, k + 1) = m.v;
      }
    }
  }
}

LtiState ModalSolution::at(double t) const {
  if (!std::isfinite(t) || t < 0.0) {
    throw std::invalid_argument("modal solution evaluated at t = " + to_text(t) +
                                ": needs finite t >= 0");
  }
  if (reduced_) return condensation_->expand(reduced_->at(t), t);
  const Eigen::Index n = phi_.cols();
  Eigen::VectorXd x(n), xd(n), xdd(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto [s1, s2] = characteristic_roots(c_(i), k_(i));
    Motion m = free_response(x0_(i), xd0_(i), s1, s2, t);
    for (Eigen::Index j = 0; j < p_.cols(); ++j) {
      if (p_(i, j) == 0.0) continue;
      const auto jj = static_cast<std::size_t>(j);
      m += p_(i, j) *
           (terms_[jj].kind == TimeTerm::Kind::table
                ? table_response(terms_[jj], knots_[jj], knot_x_[jj], knot_v_[jj], i, s1, s2, t)
                : forced_response(terms_[jj], s1, s2, t));
    }
    x(i) = m.x;
    xd(i) = m.v;
    xdd(i) = m.a;
  }
  return {phi_ * x, phi_ * xd, phi_ * xdd};
}

}  // namespace condyn
