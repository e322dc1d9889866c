#pragma once
/// Exact compatibility of right-hand sides (build_model's rank check, [solve] redundant).

#include <string>
#include <utility>
#include <vector>

#include "models/core/time_function.hpp"

namespace condyn {

/// Whether a weighted sum of time functions, Σ_k w_k f_k(t), vanishes identically on
/// [0, t_end], decided from the terms, not from samples. Every term is brought to a canonical
/// basis in which distinct elements are linearly independent on any interval: t^k; sin(ω t) and
/// cos(ω t) for ω > 0 (A sin(ω t + φ) = A cos φ sin ω t + A sin φ cos ω t; a negative ω flips the
/// sign; ω = 0 is a constant); exp(r t) for r ≠ 0 (r = 0 is a constant); H(t − s) for
/// 0 < s ≤ t_end (s ≤ 0 is a constant; s > t_end is never on inside the horizon).
/// Like elements are merged; the sum is zero when every merged coefficient is zero up to the
/// roundoff of the weights and of cos φ, sin φ (1e-9 relative to the sum of the magnitudes that
/// went into it). Two frequencies, rates or step times that differ by less than that relative
/// amount but are not equal leave the answer undecided: roundoff cannot be told from intent.
struct ZeroSumVerdict {
  enum class Kind { zero, nonzero, undecided };
  Kind kind = Kind::zero;
  /// nonzero: what survives ("1 + -1*cos(201.0619298*t)"); undecided: why.
  std::string detail;
};
[[nodiscard]] ZeroSumVerdict weighted_sum_vanishes(
    const std::vector<std::pair<double, const TimeFunction*>>& sum, double t_end);

}  // namespace condyn
