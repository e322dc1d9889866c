#include "tests/system_check.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>
#include <utility>

namespace condyn::test {
namespace {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;
using Sparse = MechanicalSystem::Sparse;

/// Relative step of the first-derivative differences, h = kStep · max(1, |x_j|): truncation
/// ~h² ≈ 1e-12 and roundoff ~eps/h ≈ 2e-10 of the function's scale, far below rel_tol = 1e-6.
constexpr double kStep = 1e-6;
/// Step along the path s ↦ (t + s, u + s u' + s²/2 a, u' + s a), as a fraction of the state's
/// time scale τ, for a Richardson-extrapolated central difference: truncation ~(h/T)⁴ for the
/// path's time scale T (1e-16 for T = τ; still 1e-12 when a rheonomic row is 10x faster than
/// τ knows), roundoff ~eps τ/h ≈ 3e-12.
constexpr double kPathStep = 1e-4;
/// The absolute floor, as a fraction of a block's natural scale (the size of the terms whose
/// difference is taken, per unit step): 50 x the worst roundoff eps/kStep ≈ 2e-10 of a central
/// difference, so cancellation in a block that is (nearly) zero is not reported.
constexpr double kFloor = 1e-8;

double max_abs(const Matrix& X) { return X.size() == 0 ? 0.0 : X.cwiseAbs().maxCoeff(); }

/// Central differences of fn in every entry of x; `largest` collects max |fn| over the evaluations.
Matrix central_jacobian(const std::function<Vector(const Vector&)>& fn, const Vector& x,
                        double& largest) {
  largest = 0.0;
  Matrix J(fn(x).size(), x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Vector xp = x, xm = x;
    const double h = kStep * std::max(1.0, std::abs(x[j]));
    xp[j] += h;
    xm[j] -= h;
    const Vector fp = fn(xp), fm = fn(xm);
    J.col(j) = (fp - fm) / (xp[j] - xm[j]);  // the step actually taken
    largest = std::max({largest, max_abs(fp), max_abs(fm)});
  }
  return J;
}

/// A reported block, copied (the system's reference is valid only until its next call).
struct Block {
  std::string name;
  Sparse S;
  Eigen::Index rows, cols;
  bool may_be_empty;  ///< the curvature blocks: 0 x 0 stands for "identically zero"
};

std::vector<Block> evaluate_blocks(MechanicalSystem& s, double t, const Vector& u, const Vector& v,
                                   const Vector& a, const Vector& w) {
  const int n = s.dofs(), m = s.constraints();
  std::vector<Block> blocks;
  blocks.push_back({"mass", s.mass(t, u), n, n, false});
  blocks.push_back({"stiffness", s.stiffness(t, u, v), n, n, false});
  blocks.push_back({"damping", s.damping(t, u, v), n, n, false});
  blocks.push_back({"constraint_jacobian", s.constraint_jacobian(t, u), m, n, false});
  blocks.push_back({"mass_jacobian", s.mass_jacobian(t, u, a), n, n, true});
  blocks.push_back({"constraint_force_jacobian", s.constraint_force_jacobian(t, u, w), n, n, true});
  blocks.push_back(
      {"constraint_product_jacobian", s.constraint_product_jacobian(t, u, a), m, n, true});
  blocks.push_back(
      {"velocity_residual_jacobian", s.velocity_residual_jacobian(t, u, v), m, n, true});
  blocks.push_back(
      {"acceleration_bias_jacobian_u", s.acceleration_bias_jacobian_u(t, u, v), m, n, true});
  blocks.push_back(
      {"acceleration_bias_jacobian_v", s.acceleration_bias_jacobian_v(t, u, v), m, n, true});
  return blocks;
}

std::vector<std::pair<Eigen::Index, Eigen::Index>> pattern(const Sparse& S) {
  std::vector<std::pair<Eigen::Index, Eigen::Index>> entries;
  for (Eigen::Index k = 0; k < S.outerSize(); ++k)
    for (Sparse::InnerIterator it(S, k); it; ++it) entries.emplace_back(it.row(), it.col());
  std::sort(entries.begin(), entries.end());
  return entries;
}

class Report {
 public:
  explicit Report(double rel_tol) : rel_tol_(rel_tol) {}

  /// The block as a dense matrix of its stated size (zero for an allowed 0 x 0); nothing, with a
  /// message, when the shape is wrong.
  std::optional<Matrix> dense(const Block& b) {
    if (b.may_be_empty && b.S.rows() == 0 && b.S.cols() == 0) return Matrix::Zero(b.rows, b.cols);
    if (b.S.rows() != b.rows || b.S.cols() != b.cols) {
      std::ostringstream s;
      s << b.name << ": shape " << b.S.rows() << "x" << b.S.cols() << ", expected " << b.rows << "x"
        << b.cols;
      messages.push_back(s.str());
      return std::nullopt;
    }
    return Matrix(b.S);
  }

  /// |got − expected| <= rel_tol · max(|got|, |expected|) + kFloor · natural, entry-wise.
  void compare(const std::string& what, const Matrix& got, const Matrix& expected, double natural) {
    if (got.size() == 0) return;
    const double tol = rel_tol_ * std::max(max_abs(got), max_abs(expected)) + kFloor * natural;
    Eigen::Index i = 0, j = 0;
    const double worst = (got - expected).cwiseAbs().maxCoeff(&i, &j);
    if (worst <= tol) return;  // NaN fails too
    std::ostringstream s;
    s.precision(12);
    s << what << ": worst entry (" << i << "," << j << "): reported " << got(i, j)
      << ", finite difference " << expected(i, j) << ", |diff| " << worst << " > tol " << tol;
    messages.push_back(s.str());
  }

  std::vector<std::string> messages;

 private:
  double rel_tol_;
};

}  // namespace

std::vector<std::string> check_system_derivatives(const MechanicalSystem& prototype, double t,
                                                  const Vector& u, const Vector& v, const Vector& a,
                                                  const Vector& w, double rel_tol) {
  const auto evaluator = prototype.clone();  // evaluation changes a system: its own copy
  MechanicalSystem& system = *evaluator;
  const int n = system.dofs(), m = system.constraints();
  Report report(rel_tol);
  if (u.size() != n || v.size() != n || a.size() != n || w.size() != m) {
    report.messages.emplace_back("check_system_derivatives: argument sizes do not match n, m");
    return report.messages;
  }

  // Patterns must not depend on the arguments: compare with the zero state.
  const auto blocks = evaluate_blocks(system, t, u, v, a, w);
  const auto at_zero = evaluate_blocks(system, 0.0, Vector::Zero(n), Vector::Zero(n),
                                       Vector::Zero(n), Vector::Zero(m));
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if (pattern(blocks[k].S) != pattern(at_zero[k].S) ||
        blocks[k].S.rows() != at_zero[k].S.rows() || blocks[k].S.cols() != at_zero[k].S.cols()) {
      report.messages.push_back(blocks[k].name +
                                ": sparsity pattern differs from the zero state's");
    }
  }
  std::vector<std::optional<Matrix>> D;
  D.reserve(blocks.size());
  for (const auto& b : blocks) D.push_back(report.dense(b));
  const auto &M = D[0], &K = D[1], &C = D[2], &A = D[3], &mass_jac = D[4], &force_jac = D[5],
             &product_jac = D[6], &psi_u = D[7], &gamma_u = D[8],
             &gamma_v = D[9];  // evaluate_blocks' order

  const auto force = [&](double tt, const Vector& uu, const Vector& vv) {
    Vector f(n);
    system.force(tt, uu, vv, f);
    return f;
  };
  const auto phi = [&](double tt, const Vector& uu) {
    Vector r(m);
    system.position_residual(tt, uu, r);
    return r;
  };
  const auto psi = [&](double tt, const Vector& uu, const Vector& vv) {
    Vector r(m);
    system.velocity_residual(tt, uu, vv, r);
    return r;
  };
  const auto gamma = [&](double tt, const Vector& uu, const Vector& vv) {
    Vector r(m);
    system.acceleration_bias(tt, uu, vv, r);
    return r;
  };
  double largest = 0.0;

  // Forces and the mass matrix.
  Matrix fd = central_jacobian([&](const Vector& x) { return force(t, x, v); }, u, largest);
  if (K) report.compare("stiffness vs -df/du", *K, -fd, largest);
  fd = central_jacobian([&](const Vector& x) { return force(t, u, x); }, v, largest);
  if (C) report.compare("damping vs -df/du'", *C, -fd, largest);
  if (M) {
    const double natural = max_abs(*M) * a.lpNorm<1>();
    fd = central_jacobian([&](const Vector& x) { return Vector(system.mass(t, x) * a); }, u,
                          largest);
    if (mass_jac) report.compare("mass_jacobian vs d(M a)/du", *mass_jac, fd, natural);
  }
  if (m == 0 || !A) return report.messages;

  // Natural scales of φ, ψ and γ (the size of their terms), from the time scale τ of the state.
  const double norm_A = max_abs(*A), u_scale = std::max(1.0, u.lpNorm<Eigen::Infinity>());
  const double v_norm = v.lpNorm<Eigen::Infinity>(), a_norm = a.lpNorm<Eigen::Infinity>();
  double tau = 1.0;
  if (v_norm > 0) tau = std::min(tau, u_scale / v_norm);
  if (a_norm > 0) tau = std::min(tau, std::max(1.0, v_norm) / a_norm);
  const Vector psi0 = psi(t, u, v), gamma0 = gamma(t, u, v);
  const double phi_scale = norm_A * u_scale;
  const double psi_scale = norm_A * (v.lpNorm<1>() + u_scale / tau) + max_abs(psi0);
  const double gamma_scale = psi_scale / tau + norm_A * a.lpNorm<1>() + max_abs(gamma0);

  // Position level, on position rows only (φ is zero on velocity rows).
  std::vector<int> p_rows;
  for (int i = 0; i < m; ++i)
    if (system.position_rows()[static_cast<std::size_t>(i)]) p_rows.push_back(i);
  fd = central_jacobian([&](const Vector& x) { return phi(t, x); }, u, largest);
  report.compare("constraint_jacobian vs dphi/du (position rows)", (*A)(p_rows, Eigen::all),
                 fd(p_rows, Eigen::all), phi_scale);

  // Along the path s ↦ (t + s, u + s u' + s²/2 a, u' + s a): dφ/dt = ψ, dψ/dt = A a − γ.
  const double h = kPathStep * tau;
  const auto path_derivative = [&](const auto& fn) {
    const auto at = [&](double s) {
      return fn(t + s, Vector(u + s * v + 0.5 * s * s * a), Vector(v + s * a));
    };
    const Vector coarse = (at(h) - at(-h)) / (2 * h), fine = (at(h / 2) - at(-h / 2)) / h;
    return Vector((4 * fine - coarse) / 3);
  };
  const Vector dphi = path_derivative(
      [&](double tt, const Vector& uu, const Vector& /*vv*/) { return phi(tt, uu); });
  report.compare("velocity_residual vs dphi/dt (position rows)", psi0(p_rows), dphi(p_rows),
                 phi_scale / tau);
  const Vector dpsi = path_derivative(psi);
  report.compare("acceleration_bias vs A a - dpsi/dt", gamma0, Vector(*A * a - dpsi), gamma_scale);

  // Velocity level and the curvature blocks.
  fd = central_jacobian([&](const Vector& x) { return psi(t, u, x); }, v, largest);
  report.compare("constraint_jacobian vs dpsi/du'", *A, fd, psi_scale);
  const auto A_at = [&](const Vector& x) { return Matrix(system.constraint_jacobian(t, x)); };
  fd = central_jacobian([&](const Vector& x) { return Vector(A_at(x).transpose() * w); }, u,
                        largest);
  if (force_jac)
    report.compare("constraint_force_jacobian vs d(A^T w)/du", *force_jac, fd,
                   norm_A * w.lpNorm<1>());
  fd = central_jacobian([&](const Vector& x) { return Vector(A_at(x) * a); }, u, largest);
  if (product_jac)
    report.compare("constraint_product_jacobian vs d(A a)/du", *product_jac, fd,
                   norm_A * a.lpNorm<1>());
  fd = central_jacobian([&](const Vector& x) { return psi(t, x, v); }, u, largest);
  if (psi_u) report.compare("velocity_residual_jacobian vs dpsi/du", *psi_u, fd, psi_scale);
  fd = central_jacobian([&](const Vector& x) { return gamma(t, x, v); }, u, largest);
  if (gamma_u)
    report.compare("acceleration_bias_jacobian_u vs dgamma/du", *gamma_u, fd, gamma_scale);
  fd = central_jacobian([&](const Vector& x) { return gamma(t, u, x); }, v, largest);
  if (gamma_v)
    report.compare("acceleration_bias_jacobian_v vs dgamma/du'", *gamma_v, fd, gamma_scale);
  return report.messages;
}

}  // namespace condyn::test
