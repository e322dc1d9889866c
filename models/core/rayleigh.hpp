#pragma once
/// Rayleigh damping C = a0 M + a1 K from two (frequency, damping ratio) pairs: the modal damping
/// ratio at ω is z(ω) = a0 / (2ω) + a1 ω / 2, so z(ω1) = z1 and z(ω2) = z2 give
///   a0 = 2 ω1 ω2 (z1 ω2 − z2 ω1) / (ω2² − ω1²),   a1 = 2 (z2 ω2 − z1 ω1) / (ω2² − ω1²).
/// The scene's pairs by frequency (models/scene/read_rayleigh.cpp) and by mode
/// (models/assembly/modal_damping.cpp) both use it.

namespace condyn {

struct RayleighCoefficients {
  double a0 = 0.0, a1 = 0.0;
};

/// From x1 != x2, both > 0, frequencies in any unit with `unit` x = ω in rad per time unit (2π for
/// cycles, 1 for rad). May return a negative or non-finite coefficient: the caller refuses those
/// with its own key.
[[nodiscard]] inline RayleighCoefficients rayleigh_coefficients(double x1, double x2, double z1,
                                                                double z2, double unit) {
  // Divided through by ω2² (r = ω1/ω2): no square of a frequency, which overflowed from 1e154
  // and underflowed below 1e-154 where a0 and a1 themselves are representable. With d = 1 − r,
  // 1 − r² = d (1 + r) and z1 − z2 r = (z1 − z2) + z2 d: d from x2 − x1, exact for close
  // frequencies, where 1 − r * r lost their difference (f and f + 1 ulp gave a ratio of 0.0417
  // for 0.05).
  const double w1 = unit * x1, w2 = unit * x2;
  const double r = x1 / x2;
  const double d = (x2 - x1) / x2;
  return {2.0 * w1 * ((z1 - z2) / d + z2) / (1.0 + r),
          2.0 * ((z2 - z1) / d + z1) / (w2 * (1.0 + r))};
}

}  // namespace condyn
