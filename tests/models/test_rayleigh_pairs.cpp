// Rayleigh damping from two (frequency, damping ratio) pairs (issue 13): the coefficients
// a0, a1 derived so that the model's damping ratio is the one asked for at each frequency.

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_rayleigh_pairs {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Two uncoupled unit masses whose natural frequencies are 1 and 10 cycles per second, with
/// `damping` as the model's damping key.
std::string two_modes(const std::string& damping) {
  const double k1 = std::pow(2.0 * kPi * 1.0, 2), k2 = std::pow(2.0 * kPi * 10.0, 2);
  return "[model]\ntype = \"matrix\"\ndofs = [\"a\", \"b\"]\nmass = [[1.0, 0.0], [0.0, 1.0]]\n"
         "stiffness = [[" +
         std::to_string(k1) + ", 0.0], [0.0, " + std::to_string(k2) + "]]\ndamping = " + damping +
         "\n[solve]\nt_end = 1.0\noutput_step = 0.1\n";
}

}  // namespace

TEST_CASE("Rayleigh damping from pairs: the asked ratios at the asked frequencies") {
  const auto scene = test::built(parse_scene_text(
      two_modes("{ rayleigh = { frequencies = [1.0, 10.0], ratios = [0.05, 0.02] } }"),
      "modes.toml"));
  const auto& C = scene.model.C;
  const auto& K = *scene.model.K;
  // Uncoupled modes: ratio_i = c_ii / (2 ω_i m_i), ω_i = sqrt(k_ii) (K written to 6 decimals
  // by std::to_string: ω to about 1e-8 relative, hence the tolerance).
  const double w1 = std::sqrt(K.coeff(0, 0)), w2 = std::sqrt(K.coeff(1, 1));
  CHECK(C.coeff(0, 0) / (2.0 * w1) == doctest::Approx(0.05).epsilon(1e-7));
  CHECK(C.coeff(1, 1) / (2.0 * w2) == doctest::Approx(0.02).epsilon(1e-7));
  CHECK(scene.report.damping.find("Rayleigh damping C = a0 M + a1 K with a0 = ") !=
        std::string::npos);
  CHECK(scene.report.damping.find("from ratio 0.05 at frequency 1") != std::string::npos);
}

TEST_CASE("Rayleigh damping from pairs: refusals name the key") {
  const auto refused = [](const std::string& damping, const std::string& words) {
    CAPTURE(damping);
    CHECK_THROWS_WITH_AS((void)parse_scene_text(two_modes(damping), "modes.toml"),
                         doctest::Contains(words.c_str()), SceneError);
  };
  refused("{ rayleigh = { frequencies = [1.0, 1.0], ratios = [0.05, 0.05] } }",
          "model.damping.rayleigh.frequencies: the two frequencies must differ");
  // A ratio much larger at the higher frequency than stiffness damping gives (z2/z1 > w2/w1).
  refused("{ rayleigh = { frequencies = [1.0, 2.0], ratios = [0.01, 0.5] } }",
          "model.damping.rayleigh: these pairs need a negative a0");
  refused("{ rayleigh = { frequencies = [1.0, 2.0], ratios = [0.01, 1.5] } }",
          "model.damping.rayleigh.ratios[2]: must be a damping ratio in [0, 1)");
  refused("{ rayleigh = { frequencies = [0.0, 2.0], ratios = [0.01, 0.02] } }",
          "model.damping.rayleigh.frequencies[1]: must be a finite frequency > 0");
  refused("{ rayleigh = { frequencies = [1.0], ratios = [0.01, 0.02] } }",
          "model.damping.rayleigh.frequencies: expected two frequencies");
  refused("{ rayleigh = { frequencies = [1.0, 2.0], ratio = [0.01, 0.02] } }",
          "model.damping.rayleigh");
  // a1 = 2 (z2 - z1 w1/w2) / (w2 (1 - (w1/w2)²)) beyond the double range: named at the
  // frequencies, not as "the damping matrix C has entries beyond the double range".
  refused("{ rayleigh = { frequencies = [1e-320, 2e-320], ratios = [0.05, 0.05] } }",
          "model.damping.rayleigh.frequencies: these frequencies give a0 = ");
}

TEST_CASE("Rayleigh damping from pairs: frequencies far apart, where their squares overflow") {
  // w2² overflowed from f = 1e154 on (and w1² underflowed below 1e-154), though a0 and a1 are
  // representable: here a0 = 4π f1 z = 0.2π and a1 = z / (π f2) = 0.05 / (π 1e155).
  const SceneSpec spec = parse_scene_text(
      two_modes("{ rayleigh = { frequencies = [1.0, 1e155], ratios = [0.05, 0.05] } }"), "m.toml");
  REQUIRE(spec.model.rayleigh);
  CHECK((*spec.model.rayleigh)[0] == doctest::Approx(0.2 * 3.14159265358979323846).epsilon(1e-15));
  CHECK((*spec.model.rayleigh)[1] ==
        doctest::Approx(0.05 / (3.14159265358979323846 * 1e155)).epsilon(1e-15));
}

TEST_CASE("Rayleigh damping from pairs: frequencies an ulp apart keep their ratios") {
  // 1 - r² for r = f1/f2 a rounding away from 1 lost the difference: f and f + 1 ulp with ratio
  // 0.05 at both gave a0 = 0.2618, a1 = 0.00663, a ratio of 0.0417 at f. The limit of equal
  // ratios z at w1 -> w2 = w is a0 = z w, a1 = z / w (z(w) = a0/(2w) + a1 w/2 = z).
  const double f2 = std::nextafter(1.0, 2.0);
  const SceneSpec spec = parse_scene_text(
      two_modes(
          "{ rayleigh = { frequencies = [1.0, 1.0000000000000002], ratios = [0.05, 0.05] } }"),
      "m.toml");
  REQUIRE(spec.model.rayleigh);
  REQUIRE(f2 == 1.0000000000000002);
  const double w = 2.0 * kPi;
  CHECK((*spec.model.rayleigh)[0] == doctest::Approx(0.05 * w).epsilon(1e-14));
  CHECK((*spec.model.rayleigh)[1] == doctest::Approx(0.05 / w).epsilon(1e-14));
  // Different ratios an ulp apart in frequency need a0 or a1 beyond any physical damping (and
  // one negative): refused as such, not from a roundoff.
  CHECK_THROWS_WITH_AS(
      (void)parse_scene_text(two_modes("{ rayleigh = { frequencies = [1.0, 1.0000000000000002], "
                                       "ratios = [0.05, 0.06] } }"),
                             "m.toml"),
      doctest::Contains("need a negative"), SceneError);
}

}  // namespace test_rayleigh_pairs
