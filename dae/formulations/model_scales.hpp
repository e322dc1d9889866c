#pragma once
/// The model's own scales: natural frequencies, a mass and a constraint coefficient, from which
/// the defaults that must not depend on units or on the output step are derived (absolute
/// tolerances per kind of unknown, Baumgarte's gains).
///
/// Frequencies are those of the linearization at t = 0 and (u0, v0) on the constraint manifold:
///   (Nᵀ K_T N) x = ω² (Nᵀ M N) x,   N an orthonormal basis of null(A),
///   K_T = −∂f/∂u + Σ_i w_i ∂(A_iᵀ)/∂u   (the geometric stiffness of the constraint forces),
/// with w_i = max(|λ_i(0)|, F_i / a_i), a_i the largest coefficient |A_ij| over the DOFs j row i
/// touches and F_i = min_j M_jj · max_j |f_j(0)| / M_jj over those with mass (the force that gives
/// the lightest the largest acceleration; max_j |f_j(0)| if all are massless): a pendulum released
/// from rest with its rod horizontal (λ(0) = 0) still gets its gravity stiffness m g / L, hence
/// ω = √(g/L), and a rod from a heavy mass to a light one carries the light one's weight. |ω²| is
/// taken (compressed members and inverted pendulums give negative ones: their time scale counts all
/// the same). Models with more than kDenseScaleLimit DOFs, or whose reduced mass is singular
/// (massless DOFs held by springs), get the diagonal estimates ω² ∈ {K_T,ii / M_ii : M_ii > 0}
/// instead, and ω_max from a few Lanczos iterations on the unconstrained pencil when M is positive
/// definite (dae/formulations/largest_frequency.hpp; the larger of it and the diagonal estimates).

#include <string>

#include "models/core/model.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

struct ModelScales {
  double omega_min = 0.0;  ///< lowest nonzero |ω| (0: none, e.g. no stiffness nor force)
  double omega_max = 0.0;  ///< highest |ω| (0: none)
  /// The frequency of the motion the run starts with: the larger Rayleigh frequency
  /// √|sᵀ K_T s / sᵀ M s| of the shapes s = a(0), the constrained acceleration the loads and the
  /// initial state give ([M Aᵀ; A 0][a; λ] = [f(0); γ(0)]), and s = v(0). A Rayleigh quotient is
  /// the mean of ω_j² over the modes weighted by their share of s (Σ c_j² ω_j² / Σ c_j²): it
  /// counts the modes the loads excite, not the stiffest bar's, which a load spread over a
  /// structure hardly moves. 0 when neither shape has one (a model at rest in equilibrium, a
  /// singular KKT matrix).
  double omega_start = 0.0;
  /// max_i |a_i(0)| of that acceleration (0: none known).
  double acceleration_start = 0.0;
  double mass = 1.0;         ///< mean of the positive diagonal entries of M
  double coefficient = 1.0;  ///< largest |A_ij| at t = 0 (1 without constraints)
  /// rms of (A Aᵀ)⁻¹ δφ, δφ_i = ±eps ℓ a_i the position rows' roundoff (ℓ the rods' longest
  /// length, PointMassSystem::row_length_scale, else 1; a_i a row's largest |A_ij|; signs from a
  /// fixed pseudo-random sequence): the displacement a Newton correction cannot resolve, which A Aᵀ
  /// amplifies as it grows ill-conditioned (a chain's, with its number of links). Computed for
  /// systems with curvature (nonlinear rows); 0 otherwise or when A Aᵀ is singular.
  double row_noise = 0.0;
  std::string method;      ///< "constrained eigenvalues" or "diagonal estimate"
  std::string method_max;  ///< how ω_max was found when not as `method` ("Lanczos")
};

/// Above this many DOFs the frequencies are diagonal estimates: the eigenproblem is dense (QR of
/// Aᵀ and a generalized eigensolve, O(n³); docs/benchmarks.md) and runs before every solve.
inline constexpr int kDenseScaleLimit = 400;

[[nodiscard]] ModelScales model_scales(const Model& model);

/// Absolute tolerances per kind of unknown. Displacements: [solve] atol (model units). The others,
/// unless the scene sets them, follow from it so that an error of that size moves the
/// displacements by atol:
///   velocity    atol_v = atol / t_end            (sustained over the run, but over at most
///                                                 1000 / ω_min; a looser atol / T cost the car
///                                                 axis a digit at rtol 1e-10: its motion is
///                                                 forced, slower than its lowest mode), but at
///                                                 least the roundoff of v: 16 eps max|v(0)|, and
///                                                 under GGL eps max|u(0)| ω_max / rtol^(1/4), u's
///                                                 roundoff over a BDF step
///   multiplier  atol_λ = atol · m / (T² · a)     (a force error Δf sustained over the model's
///                                                 slowest natural time scale T = min(1/ω_min,
///                                                 t_end) displaces a mass m by Δf T²/m; λ is a
///                                                 force per unit coefficient a = max|A_ij|)
///   GGL's μ     atol_μ = atol_v / a              (A_pᵀ μ is a velocity correction), but at
///                                                 least 16 row_noise / T: μ's weight is
///                                                 (h/T) / atol_μ and the μ a step needs to
///                                                 correct the rows' roundoff is row_noise / h
struct AbsoluteTolerances {
  double displacement = 0.0, velocity = 0.0, multiplier = 0.0, mu = 0.0;
  /// The smallest atol_μ the position rows' roundoff allows (16 row_noise / T; 0: none known),
  /// which a scene's own atol_mu may go below (the failure advice then names it).
  double mu_floor = 0.0;
  /// T above: the higher-index Newton weights use (h/T)^(k−1), a pure number, instead of h^(k−1),
  /// whose size depended on the unit of time.
  double time_scale = 1.0;
  /// m above (ModelScales::mass): rows whose lightest mass lies far below it get a smaller
  /// multiplier atol (IntegratorOptions::multiplier_mass).
  double mass = 1.0;
  /// First step of the higher-index schemes: √rtol / ω_max (at most t_end), the step at which
  /// BDF1's local error h² |y''| / 2 is about rtol |y| on the model's fastest time scale. A step
  /// far below it makes index3's Newton matrix singular in double precision (its condition grows
  /// like 1/h²): the oblique pendulum failed to start at h = 1e-10, index3 failed to restart a
  /// table drive at h = 2.7e-11. The guess below did not pay there: GGL on the quickstart took
  /// 747 steps from it against 449 from this one.
  double first_step = 0.0;
  /// First step under elimination (linear models): √rtol / ω_start (ModelScales::omega_start;
  /// ω_max when it is 0), the same rule on the time scale of the motion the run starts with, and
  /// at most √(2 atol / max|a_i(0)|), the step over which a DOF starting from rest moves by atol,
  /// which BDF1's error test holds it to (a step load on a soft oscillator at atol 1e-9 failed
  /// the test twice from √rtol / ω = 1e-3 and passed at 6e-5; √(2 atol / a) = 4.5e-5). No floor:
  /// elimination's unknowns are all in the error test and its Newton matrix stays well
  /// conditioned as h → 0; a DOF at 2e16 on a unit spring at rtol 0.5 passes the error test only
  /// at steps of about 1e-10, which IDA's ten step cuts from a floored 0.05 could not reach. The
  /// error test still decides: this spares the steps that double from IDA's own guess,
  /// 0.5 / ‖y'(0)‖ (6e-7 s on a braced wall whose first steps pass the error test at 4e-6 s;
  /// docs/schemes.md).
  double first_step_from_motion = 0.0;
  std::string rule;  ///< one line for `condyn info`
  /// The model's scales they were derived from (kept for what else needs them: RATTLE's
  /// stability limit), so that a plan computes them once.
  ModelScales scales;
};

[[nodiscard]] AbsoluteTolerances absolute_tolerances(const Model& model, const SolveSpec& settings);

}  // namespace condyn
