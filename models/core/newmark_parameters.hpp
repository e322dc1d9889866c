#pragma once
/// The Newmark family's parameters ([solve] newmark, hht, generalized_alpha; docs/schemes.md
/// "The Newmark family"). Every member is one generalized-α method in the notation of Chung and
/// Hulbert (1993), "A time integration algorithm for structural dynamics with improved numerical
/// dissipation: the generalized-α method", J. Appl. Mech. 60, 371-375:
///
///   M [(1 − αm) a_{n+1} + αm a_n] = (1 − αf) F_{n+1} + αf F_n
///   u_{n+1} = u_n + h v_n + h² [(½ − β) a_n + β a_{n+1}]
///   v_{n+1} = v_n + h [(1 − γ) a_n + γ a_{n+1}]
///
/// - Newmark (1959): αm = αf = 0 (β, γ as given; average acceleration β = ¼, γ = ½);
/// - HHT-α (Hilber, Hughes and Taylor 1977), α ∈ [−⅓, 0]: αm = 0, αf = −α, γ = ½ − α,
///   β = (1 − α)²/4;
/// - generalized-α from ρ∞ ∈ [0, 1] (Chung and Hulbert's eq. 25): αm = (2ρ∞ − 1)/(ρ∞ + 1),
///   αf = ρ∞/(ρ∞ + 1), γ = ½ − αm + αf, β = ¼ (1 − αm + αf)².

#include <optional>
#include <string>
#include <string_view>

#include "models/core/scheme.hpp"

namespace condyn {

/// One generalized-α parameter set.
struct AlphaParameters {
  double alpha_m = 0.0, alpha_f = 0.0, beta = 0.25, gamma = 0.5;
};

/// How the Newmark family holds the constraints ([solve] newmark_constraints): at index 3
/// (positions and multipliers, the default) or stabilized at index 2 (the velocity constraints
/// too, through a second multiplier μ on the positions: GGL's form, Arnold and Brüls 2007).
enum class NewmarkConstraints { index3, stabilized };
[[nodiscard]] const char* to_string(NewmarkConstraints form);
/// The form named s ("index3", "stabilized"), or nothing.
[[nodiscard]] std::optional<NewmarkConstraints> newmark_constraints_from_string(std::string_view s);

/// What a scene gives of the Newmark family's parameters (each unset: its default).
struct NewmarkFamilySpec {
  NewmarkConstraints constraints = NewmarkConstraints::index3;
  std::optional<double> newmark_beta, newmark_gamma;  ///< newmark = { beta, gamma }
  std::optional<double> hht_alpha;                    ///< hht = { alpha }
  std::optional<double> rho_inf;                      ///< generalized_alpha = { rho_inf }
  /// generalized_alpha = { alpha_m, alpha_f, beta, gamma }: all four, or none.
  std::optional<AlphaParameters> alpha_direct;
};

inline constexpr double kDefaultNewmarkBeta = 0.25, kDefaultNewmarkGamma = 0.5;
inline constexpr double kDefaultHhtAlpha = -0.05;
inline constexpr double kDefaultRhoInf = 0.9;

[[nodiscard]] AlphaParameters newmark_parameters(double beta, double gamma);
[[nodiscard]] AlphaParameters hht_parameters(double alpha);
[[nodiscard]] AlphaParameters generalized_alpha_parameters(double rho_inf);
/// The parameter set `scheme` (newmark, hht or generalized_alpha) runs with under `spec`.
/// Throws std::invalid_argument for another scheme.
[[nodiscard]] AlphaParameters alpha_parameters(Scheme scheme, const NewmarkFamilySpec& spec);

/// What is wrong with a value, as the last part of "FILE:LINE: key: problem", or nothing.
/// Newmark: γ ∈ [½, 1] (γ < ½ amplifies, Newmark 1959) and β ≥ γ/2, the condition of unconditional
/// stability (Hughes 1987, The Finite Element Method, §9.1.2): below it (linear acceleration,
/// β = 1/6; the central difference, β = 0) the method is stable only for h ω below
/// 1/√(γ/2 − β), which no step size control can promise for every mode of a model.
[[nodiscard]] std::optional<std::string> newmark_beta_problem(double beta, double gamma);
[[nodiscard]] std::optional<std::string> newmark_gamma_problem(double gamma);
/// HHT: α ∈ [−⅓, 0], the range of unconditional stability and second order (HHT 1977).
[[nodiscard]] std::optional<std::string> hht_alpha_problem(double alpha);
/// ρ∞ ∈ [0, 1].
[[nodiscard]] std::optional<std::string> rho_inf_problem(double rho_inf);
/// Chung and Hulbert's unconditional stability (their eq. 22): αm ≤ αf ≤ ½ and
/// β ≥ ¼ + ½ (αf − αm); and γ ≥ ½ − αm + αf (below it the method amplifies; equal: second order).
[[nodiscard]] std::optional<std::string> alpha_direct_problem(const AlphaParameters& p);

/// Whether the method damps the highest frequencies (spectral radius below 1 as h ω → ∞): γ above
/// ½ (Newmark, first order) or αf above αm (HHT with α < 0, generalized-α with ρ∞ < 1, where
/// γ − ½ = αf − αm). Average acceleration, HHT with α = 0 and generalized-α with ρ∞ = 1 do not.
[[nodiscard]] bool damps_high_frequencies(const AlphaParameters& p);

/// "β = 0.25, γ = 0.5 (αm = 0, αf = 0)"-like words for a run's note.
[[nodiscard]] std::string describe(Scheme scheme, const AlphaParameters& p);

}  // namespace condyn
