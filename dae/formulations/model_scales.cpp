#include "dae/formulations/model_scales.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <sstream>

#include "dae/formulations/largest_frequency.hpp"
#include "dae/linsolve/kkt.hpp"
#include "models/core/eigen_decompositions.hpp"

namespace condyn {

namespace {

/// Frequencies² (absolute values, ascending) of K x = ω² M x on null(A), or nothing when the
/// reduced mass is not positive definite.
std::optional<Eigen::VectorXd> constrained_eigenvalues(const Eigen::MatrixXd& M,
                                                       const Eigen::MatrixXd& K,
                                                       const Eigen::MatrixXd& A) {
  const Eigen::Index n = M.rows();
  Eigen::MatrixXd N;
  if (A.rows() == 0) {
    N = Eigen::MatrixXd::Identity(n, n);
  } else {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A.transpose());
    const Eigen::Index rank = qr.rank();
    const Eigen::MatrixXd Q = qr.householderQ();
    N = Q.rightCols(n - rank);
  }
  if (N.cols() == 0) return Eigen::VectorXd();
  const Eigen::MatrixXd Mr = N.transpose() * M * N;
  const Eigen::MatrixXd Kt = N.transpose() * K * N;
  const Eigen::MatrixXd Kr = 0.5 * Kt + 0.5 * Kt.transpose();  // no overflow at 1e308
  const Eigen::LLT<Eigen::MatrixXd> llt(Mr);
  if (llt.info() != Eigen::Success) return std::nullopt;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kr, Mr,
                                                                      Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return std::nullopt;
  Eigen::VectorXd w = eig.eigenvalues().cwiseAbs();
  std::sort(w.begin(), w.end());
  return w;
}

/// ω² estimates K_ii / M_ii over the DOFs with mass (Rayleigh quotients of unit vectors).
Eigen::VectorXd diagonal_estimates(const Eigen::SparseMatrix<double>& M,
                                   const Eigen::SparseMatrix<double>& K) {
  const Eigen::VectorXd m = M.diagonal(), k = K.diagonal();
  std::vector<double> out;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    if (m[i] > 0.0) out.push_back(std::abs(k[i]) / m[i]);
  }
  std::sort(out.begin(), out.end());
  return Eigen::Map<const Eigen::VectorXd>(out.data(), static_cast<Eigen::Index>(out.size()));
}

/// The length the position rows compute with: the rods' of a truss, else 1 (angles in radians, a
/// model in metres).
double row_length(const MechanicalSystem& system) {
  const double length = system.row_length_scale();
  return length > 0.0 ? length : 1.0;
}

/// ModelScales::row_noise: y = −(A Aᵀ)⁻¹ δφ from [I Aᵀ; A 0][x; y] = [0; δφ] (x = −Aᵀ y), the
/// matrix of GGL's rows u' − v + Aᵀμ and φ(u) = 0 once the velocities are set aside.
double row_noise(const Eigen::SparseMatrix<double>& A, double length) {
  const Eigen::Index n = A.cols(), m = A.rows();
  Eigen::SparseMatrix<double> identity(n, n);
  identity.setIdentity();
  const KktLu lu(kkt_matrix(identity, A));
  if (lu.info() != Eigen::Success) return 0.0;  // dependent rows: no estimate
  Eigen::VectorXd largest = Eigen::VectorXd::Zero(m);
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      largest[it.row()] = std::max(largest[it.row()], std::abs(it.value()));
  // Roundoff has no pattern the rows could cancel: signs from a fixed seed, so that every run
  // and platform gets the same estimate (std::mt19937's sequence is the standard's). The
  // amplified part is a few smooth modes' share of the signs, which varies from one draw to the
  // next (five times between two draws on a chain of 10⁵ links): the rms over kNoiseDraws.
  constexpr int kNoiseDraws = 4;
  std::mt19937 signs(1);
  const double ulp = std::numeric_limits<double>::epsilon() * length;
  double sum = 0.0;
  for (int draw = 0; draw < kNoiseDraws; ++draw) {
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
    for (Eigen::Index i = 0; i < m; ++i)
      rhs[n + i] = ((signs() & 1U) != 0 ? ulp : -ulp) * largest[i];
    const Eigen::VectorXd y = lu.solve(rhs).tail(m);
    if (!y.allFinite()) return 0.0;
    sum += y.squaredNorm();
  }
  return std::sqrt(sum / (kNoiseDraws * static_cast<double>(m)));
}

/// √|sᵀ K s / sᵀ M s|, the Rayleigh frequency of a shape s; 0 when s moves no mass.
double rayleigh_frequency(const Eigen::SparseMatrix<double>& M,
                          const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& s) {
  const double kinetic = s.dot(M * s), elastic = std::abs(s.dot(K * s));
  if (!(kinetic > 0.0) || !std::isfinite(elastic)) return 0.0;
  const double w2 = elastic / kinetic;
  return std::isfinite(w2) ? std::sqrt(w2) : 0.0;
}

/// ModelScales::omega_start and acceleration_start: the Rayleigh frequencies of the initial
/// acceleration a(0) (from `kkt`, [M Aᵀ; A 0] factored, or M alone without constraints:
/// [a; λ] = [f; γ]) and of v(0), the larger, and max |a_i(0)|; 0 where there is none (a model at
/// rest in equilibrium, a singular KKT matrix).
void start_motion(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                  const KktLu& kkt, const Eigen::VectorXd& f, const Eigen::VectorXd& gamma,
                  const Eigen::VectorXd& v0, ModelScales& s) {
  s.omega_start = rayleigh_frequency(M, K, v0);
  if (kkt.info() != Eigen::Success) return;
  Eigen::VectorXd rhs(f.size() + gamma.size());
  rhs << f, gamma;
  const Eigen::VectorXd a = kkt.solve(rhs).head(f.size());
  if (!a.allFinite() || a.size() == 0) return;
  s.omega_start = std::max(s.omega_start, rayleigh_frequency(M, K, a));
  s.acceleration_start = a.cwiseAbs().maxCoeff();
}

}  // namespace

ModelScales model_scales(const Model& model) {
  const auto evaluator = model.evaluator();
  MechanicalSystem& system = *evaluator;
  const int n = system.dofs(), m = system.constraints();
  const double t = 0.0;
  ModelScales s;
  const Eigen::SparseMatrix<double> M = system.mass(t, model.u0);
  {
    double total = 0.0;
    int count = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (M.coeff(i, i) > 0.0) {
        total += M.coeff(i, i);
        ++count;
      }
    }
    if (count > 0) s.mass = total / count;
  }
  Eigen::VectorXd f(n);
  system.force(t, model.u0, model.v0, f);
  Eigen::SparseMatrix<double> K = system.stiffness(t, model.u0, model.v0);
  Eigen::SparseMatrix<double> A;
  if (m > 0) {
    A = system.constraint_jacobian(t, model.u0);
    s.coefficient = 0.0;
    for (Eigen::Index k = 0; k < A.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
        s.coefficient = std::max(s.coefficient, std::abs(it.value()));
    if (!(s.coefficient > 0.0)) s.coefficient = 1.0;
  }
  Eigen::VectorXd gamma = Eigen::VectorXd::Zero(m);
  if (m > 0) system.acceleration_bias(t, model.u0, model.v0, gamma);
  // The initial acceleration's matrix (its multipliers give the geometric stiffness below).
  const KktLu lu(m > 0 ? kkt_matrix(M, A) : M);
  if (m > 0 && system.has_curvature()) {
    // The geometric stiffness of the constraint forces, with each multiplier at least the size
    // the applied forces give it (see the header).
    Eigen::VectorXd lambda0 = Eigen::VectorXd::Zero(m);
    if (lu.info() == Eigen::Success) {
      Eigen::VectorXd rhs(n + m);
      rhs << f, gamma;
      const Eigen::VectorXd sol = lu.solve(rhs);
      if (sol.allFinite()) lambda0 = sol.tail(m);
    }
    const Eigen::SparseMatrix<double> At = A.transpose();
    Eigen::VectorXd w(m);
    for (int i = 0; i < m; ++i) {
      // The force that gives the row's lightest DOF the largest acceleration the loads give any
      // of its DOFs, over the row's largest coefficient (λ A is a force): a rod between a 1e6 kg
      // and a 1e-6 kg mass under gravity carries about 1e-6 g, not the heavy mass's 1e6 g
      // (which made ω 3e6 for a double pendulum whose frequencies are 3.1). Rows over massless
      // DOFs alone: the largest force on them.
      double force = 0.0, acceleration = 0.0, lightest = 0.0, coefficient = 0.0;
      for (Eigen::SparseMatrix<double>::InnerIterator it(At, i); it; ++it) {
        const double load = std::abs(f[it.row()]), mass = M.coeff(it.row(), it.row());
        force = std::max(force, load);
        if (mass > 0.0) {
          acceleration = std::max(acceleration, load / mass);
          lightest = lightest > 0.0 ? std::min(lightest, mass) : mass;
        }
        coefficient = std::max(coefficient, std::abs(it.value()));
      }
      const double carried = lightest > 0.0 ? acceleration * lightest : force;
      w[i] = std::max(std::abs(lambda0[i]), coefficient > 0.0 ? carried / coefficient : 0.0);
    }
    const auto& G = system.constraint_force_jacobian(t, model.u0, w);
    if (G.size() > 0) K += G;
    s.row_noise = row_noise(A, row_length(system));
  }
  start_motion(M, K, lu, f, gamma, model.v0, s);
  std::optional<Eigen::VectorXd> w2;
  if (n <= kDenseScaleLimit) {
    w2 = constrained_eigenvalues(Eigen::MatrixXd(M), Eigen::MatrixXd(K),
                                 m > 0 ? Eigen::MatrixXd(A) : Eigen::MatrixXd(0, n));
  }
  s.method = w2 ? "constrained eigenvalues" : "diagonal estimate";
  // Beyond the dense solver, the top of the spectrum by Lanczos: the diagonal estimates are
  // Rayleigh quotients of unit vectors, lower bounds of ω²_max that can be far below it.
  std::optional<double> lanczos;
  if (!w2) {
    w2 = diagonal_estimates(M, K);
    lanczos = largest_eigenvalue(K, M);
    if (lanczos) s.method_max = "Lanczos";
  }
  if (w2->size() > 0 && std::max(w2->maxCoeff(), lanczos.value_or(0.0)) > 0.0) {
    const double top = std::max(w2->maxCoeff(), lanczos.value_or(0.0));
    s.omega_max = std::sqrt(top);
    // Rigid-body modes come out at roundoff relative to the largest: they set no time scale.
    const double floor = 1e-10 * top;
    for (const double v : *w2) {
      if (v > floor) {
        s.omega_min = std::sqrt(v);
        break;
      }
    }
  }
  return s;
}

namespace {

/// The largest derived absolute tolerance: its error weight, 1e-300, still a normal double.
constexpr double kMaxDerivedAtol = 1e300;

/// How many times the rows' roundoff over T GGL's μ atol must be (ModelScales::row_noise): the
/// hanging chains measured (docs/schemes.md) needed from 0.25 to some 20 times it; 16, as the
/// velocities' roundoff floor.
constexpr double kRowNoiseUlps = 16.0;

/// The velocities' roundoff, below which Newton cannot converge on them: 16 eps max|v(0)| (the
/// four-bar, |v0| = 6, at atol 1e-15 over 2 s, atol_v 5e-16, failed at t = 6e-8; 16 eps |v0| is
/// 2e-14), and eps max|u(0)| / h: the BDF derivative u' = (α u + ...) / h carries u's roundoff
/// over the step, and u' − v = 0 passes it on to v. h is the step at which BDF of order 3 makes
/// a local error of rtol on the fastest time scale, rtol^(1/4) / ω_max: A01's pendulum released
/// from rest (v0 = 0, |u| = 1 m, ω = 3.13, rtol 1e-10, steps of 1.7e-3 s) failed at t = 1517
/// and 1953 s with atol_v 1.1e-14 and 3.1e-14 and passed with 5e-14 and 1e-13; this gives 2.2e-13.
/// GGL's only: its v is also corrected by A_pᵀμ; Baumgarte and index1 ran A01's 2000 s at
/// 3.1e-15, and Baumgarte over 20 s lost half a digit at 2.2e-13.
double velocity_roundoff(const Model& model, const ModelScales& s, const SolveSpec& settings) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const auto largest = [](const Eigen::VectorXd& x) {
    return x.size() > 0 ? x.cwiseAbs().maxCoeff() : 0.0;
  };
  const double step = std::pow(settings.rtol, 0.25) / s.omega_max;
  const bool ggl = settings.scheme == Scheme::ggl;
  const double derivative = ggl && s.omega_max > 0.0 ? eps * largest(model.u0) / step : 0.0;
  return std::max(16.0 * eps * largest(model.v0), derivative);
}

}  // namespace

AbsoluteTolerances absolute_tolerances(const Model& model, const SolveSpec& settings) {
  const ModelScales s = model_scales(model);
  const double t_end = settings.t_end > 0.0 ? settings.t_end : 1.0;
  // The slowest time scale: the lowest natural period's 1/ω, at most the run's length.
  const double T = s.omega_min > 0.0 ? std::min(1.0 / s.omega_min, t_end) : t_end;
  AbsoluteTolerances a;
  a.scales = s;
  a.displacement = settings.atol;
  // Sustained over the run, but over no more than a thousand of the slowest natural time
  // scales (an oscillator turns a velocity error into a displacement of Δv/ω, not Δv·t_end), and
  // never below 1e-30 atol per unit time: t_end = 1e300 gave 1e-310, an infinite error weight.
  // (Over 1e3 / ω_min whatever t_end, the runs shorter than that met u's roundoff: the four-bar
  // and the hanging chain at atol 1e-12 over 2 s failed under GGL.)
  const double sustained = s.omega_min > 0.0 ? std::min(t_end, 1e3 / s.omega_min) : t_end;
  a.velocity = settings.atol_velocity.value_or(std::max(
      {a.displacement / sustained, velocity_roundoff(model, s, settings), 1e-30 * a.displacement}));
  // The derived ones never below kMinAtol, where error weights stop fitting in a double's
  // error norm (a tiny mass or a huge coefficient could take them there), nor above
  // kMaxDerivedAtol: masses of 1e308 or an atol of 1e307 made them infinite, and the run
  // stopped on 'atol_multiplier must be > 0 and finite', a key nobody set.
  const auto usable = [](double atol) {
    return std::isnan(atol) ? kMaxDerivedAtol : std::clamp(atol, kMinAtol, kMaxDerivedAtol);
  };
  a.velocity = usable(a.velocity);
  a.multiplier =
      settings.atol_multiplier.value_or(usable(a.displacement * s.mass / (T * T * s.coefficient)));
  // μ's weight is (h/T) / atol_μ, and a step of size h needs μ of row_noise / h to correct the
  // rows' roundoff: far below row_noise / T Newton cannot converge on μ. A 30° hanging chain of
  // 30,000 links (row_noise 4.4e-10, T = 0.21) failed at t = 9.4e-6 with atol_μ = atol_v = 1e-10
  // and ran from 1e-9.
  a.mu_floor = kRowNoiseUlps * s.row_noise / T;
  a.mu = settings.atol_mu.value_or(usable(std::max(a.velocity / s.coefficient, a.mu_floor)));
  a.time_scale = T;
  a.mass = s.mass;
  const auto step_at = [&](double omega) {
    return std::sqrt(settings.rtol) * (omega > 0.0 ? std::min(1.0 / omega, t_end) : t_end);
  };
  // The higher-index schemes: the fastest time scale's step (see the header).
  a.first_step = step_at(s.omega_max);
  // Elimination: the time scale of the motion the run starts with, and from rest the step over
  // which the largest initial acceleration moves its DOF by atol. Linear models only: a
  // mechanism's start keeps the fastest time scale.
  const bool linear = !model.is_nonlinear();
  const double start = linear && s.omega_start > 0.0 ? s.omega_start : s.omega_max;
  a.first_step_from_motion = step_at(start);
  if (linear && s.acceleration_start > 0.0) {
    const double from_rest = std::sqrt(2.0 * a.displacement / s.acceleration_start);
    a.first_step_from_motion = std::min(a.first_step_from_motion, from_rest);
  }
  std::ostringstream r;
  r.precision(3);
  r << "atol displacement " << a.displacement << ", velocity " << a.velocity
    << (settings.atol_velocity ? " (scene)" : "") << ", multiplier " << a.multiplier
    << (settings.atol_multiplier ? " (scene)" : "") << ", mu " << a.mu
    << (settings.atol_mu ? " (scene)" : "");
  // Said only where it decides: the floor raised the derived value, or a scene's lies below it.
  if (a.mu < a.mu_floor) {
    r << " (below the constraint rows' roundoff floor " << a.mu_floor << ")";
  } else if (!settings.atol_mu && a.mu_floor > a.velocity / s.coefficient) {
    r << " (the constraint rows' roundoff floor)";
  }
  r << "; time scale T = " << T << " (lowest " << s.method << " frequency " << s.omega_min
    << ", t_end " << t_end << "), highest frequency " << s.omega_max
    << (s.method_max.empty() ? "" : " (" + s.method_max + ")") << ", first step "
    << a.first_step_from_motion << " under elimination ("
    << (start != s.omega_max ? "frequency of the initial motion " : "highest frequency ") << start
    << ", largest initial acceleration " << s.acceleration_start << "), " << a.first_step
    << " under the higher-index schemes, mass " << s.mass << ", coefficient " << s.coefficient;
  a.rule = r.str();
  return a;
}

}  // namespace condyn
