// Rayleigh damping naming modes, damping = { rayleigh = { modes = [i, j], ratios = [z1, z2] } }
// (models/assembly/modal_damping.cpp): the two modes get their ratios, the coefficients are those
// the same frequencies give (beyond the dense limit too, where Lanczos finds them), massless DOFs
// are condensed as `condyn modes` condenses them, and the refusals name the key.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "dae/formulations/natural_modes.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/pencil_modes.hpp"
#include "models/core/rayleigh.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"
#include "tests/shear_building.hpp"

using namespace condyn;

namespace test_rayleigh_modes {

using condyn::test::ShearBuilding;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// A mode's ratio φᵀCφ / (2ω) from mass-normalized shapes: a few roundings of O(1) sums and the
// dense eigensolver's few eps on ω²; 64 eps relative (observed 1.3 eps; the two Cs differ by 1.1
// eps).
constexpr double kRatioTolerance = 64 * kEps;
// Lanczos' ω² against the closed form, as tests/dae/test_natural_modes.cpp bounds them: its
// tolerance on the Ritz values, 10 kModeTolerance relative, plus the factorization's backward
// error, 64 eps of ω²_max (added by the caller, scaled).
constexpr double kLanczosTolerance = 10 * kModeTolerance;
constexpr double kFactorRoundoff = 64 * kEps;

std::string with_damping(const std::string& damping, const ShearBuilding& b = {.storeys = 5}) {
  return test::replace(test::shear_building_scene(b),
                       "stiffness = ", "damping = " + damping + "\nstiffness = ");
}

Model model_of(const std::string& text) { return build_model(parse_scene_text(text, "d.toml")); }

/// φᵀCφ / (2ω) of mode j (0-based) of the undamped constrained model.
double damping_ratio(const Model& model, const NaturalModes& modes, int j) {
  const Eigen::VectorXd phi = modes.shapes.col(j);
  return phi.dot(model.C * phi) / (2.0 * modes.omega[j]);
}

/// A shear building of n storeys (mass m, storey stiffness k) as a matrix model read from Matrix
/// Market files in `box`: sparse at any size (shear_building_scene writes dense rows).
std::string shear_building_files(const test::Sandbox& box, const ShearBuilding& b,
                                 const std::string& damping) {
  const int n = b.storeys;
  std::ostringstream m, k, dofs;
  m.precision(17);
  k.precision(17);
  m << "%%MatrixMarket matrix coordinate real general\n" << n << " " << n << " " << n << "\n";
  k << "%%MatrixMarket matrix coordinate real symmetric\n"
    << n << " " << n << " " << 2 * n - 1 << "\n";
  for (int i = 1; i <= n; ++i) {
    m << i << " " << i << " " << b.mass << "\n";
    k << i << " " << i << " " << (i < n ? 2.0 : 1.0) * b.stiffness << "\n";  // the top: one spring
    if (i < n) k << i + 1 << " " << i << " " << -b.stiffness << "\n";
    dofs << (i > 1 ? ", " : "") << "\"u" << i << "\"";
  }
  box.write("M.mtx", m.str());
  box.write("K.mtx", k.str());
  return "[model]\ntype = \"matrix\"\ndofs = [" + dofs.str() +
         "]\nmass = { file = \"M.mtx\" }\nstiffness = { file = \"K.mtx\" }\ndamping = " + damping +
         "\n[solve]\nt_end = 1.0\noutput_step = 0.5\n";
}

std::string refusal(const std::string& text) {
  try {
    (void)model_of(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("Rayleigh damping by modes gives the two modes their ratios") {
  const Model model =
      model_of(with_damping("{ rayleigh = { modes = [1, 3], ratios = [0.05, 0.02] } }"));
  const NaturalModes modes = natural_modes(model, 5);
  CHECK(std::abs(damping_ratio(model, modes, 0) - 0.05) <= kRatioTolerance * 0.05);
  CHECK(std::abs(damping_ratio(model, modes, 2) - 0.02) <= kRatioTolerance * 0.02);
  // The same C as the frequencies of those modes give (to 17 digits: a few eps of C).
  std::ostringstream f;
  f.precision(17);
  f << "{ rayleigh = { frequencies = [" << mode_frequency(modes.omega[0]) << ", "
    << mode_frequency(modes.omega[2]) << "], ratios = [0.05, 0.02] } }";
  const Model by_frequency = model_of(with_damping(f.str()));
  const Eigen::MatrixXd difference = Eigen::MatrixXd(model.C - by_frequency.C);
  CHECK(difference.cwiseAbs().maxCoeff() <=
        kRatioTolerance * Eigen::MatrixXd(model.C).cwiseAbs().maxCoeff());
}

TEST_CASE("Rayleigh damping by modes beyond the dense limit: Lanczos, as condyn modes finds them") {
  // 2,500 storeys: beyond the dense limit of 2,000 DOFs, where the modes were refused before.
  const ShearBuilding b{.storeys = 2500, .mass = 2.0, .stiffness = 3.0e3};
  const test::Sandbox box;
  const Model model = build_model(
      parse_scene_file(box.write("s.toml", shear_building_files(box, b,
                                                                "{ rayleigh = { modes = [1, 3], "
                                                                "ratios = [0.05, 0.05] } }"))
                           .string()));
  REQUIRE(static_cast<double>(model.dofs()) * model.dofs() > kMaxDenseModeEntries);
  const NaturalModes modes = natural_modes(model, 3);
  CHECK_FALSE(modes.dense);  // the sparse path
  // The same C as `frequencies` gives at the frequencies `condyn modes` finds (17 digits: the
  // same solver on the same pencil, so a few eps of C).
  std::ostringstream f;
  f.precision(17);
  f << "{ rayleigh = { frequencies = [" << mode_frequency(modes.omega[0]) << ", "
    << mode_frequency(modes.omega[2]) << "], ratios = [0.05, 0.05] } }";
  const Model by_frequency = build_model(
      parse_scene_file(box.write("f.toml", shear_building_files(box, b, f.str())).string()));
  const double c_max = Eigen::MatrixXd(model.C).cwiseAbs().maxCoeff();
  CHECK(Eigen::MatrixXd(model.C - by_frequency.C).cwiseAbs().maxCoeff() <= kRatioTolerance * c_max);
  // And the closed form's: with equal ratios a0 = 2 z ω1 ω3 / (ω1 + ω3), a1 = 2 z / (ω1 + ω3)
  // move by at most twice the ω's relative error, half their ω²'s (kLanczosTolerance, and the
  // factorization's error of ω²_max = 4 k/m relative to ω1²); C's entries are sums of a0 M and
  // a1 K, so its largest moves by at most as much relative to itself (observed 5.8e-15).
  const double w1 = test::shear_building_omega(b, 1), w3 = test::shear_building_omega(b, 3);
  const auto [a0, a1] = rayleigh_coefficients(w1, w3, 0.05, 0.05, 1.0);
  const Eigen::SparseMatrix<double> exact = a0 * model.M + a1 * *model.K;
  const double relative =
      kLanczosTolerance + kFactorRoundoff * 4.0 * b.stiffness / b.mass / (w1 * w1);
  const double off = Eigen::MatrixXd(model.C - exact).cwiseAbs().maxCoeff() / c_max;
  CAPTURE(off);
  CHECK(off <= relative);
}

TEST_CASE("Rayleigh damping by modes condenses massless DOFs, as condyn modes does") {
  // Springs of 2k in series through massless DOFs: the building's closed form, once refused.
  const ShearBuilding b{.storeys = 6, .mass = 1.5, .stiffness = 30.0, .massless_midpoints = true};
  const Model model = model_of(test::replace(test::shear_building_scene(b), "stiffness = ",
                                             "damping = { rayleigh = { modes = [1, 3], ratios = "
                                             "[0.05, 0.05] } }\nstiffness = "));
  const double w1 = test::shear_building_omega(b, 1), w3 = test::shear_building_omega(b, 3);
  const auto [a0, a1] = rayleigh_coefficients(w1, w3, 0.05, 0.05, 1.0);
  const Eigen::SparseMatrix<double> exact = a0 * model.M + a1 * *model.K;
  // The dense path: each ω² within 64 eps of ω²_max = 4 k/m (of the storeys' own springs, 2k
  // each in series), ω1's relative error that over ω1², doubled for a0 (as above; observed
  // 1.6e-15).
  const double relative = kFactorRoundoff * 4.0 * 2.0 * b.stiffness / b.mass / (w1 * w1);
  const double c_max = Eigen::MatrixXd(model.C).cwiseAbs().maxCoeff();
  const double off = Eigen::MatrixXd(model.C - exact).cwiseAbs().maxCoeff() / c_max;
  CAPTURE(off);
  CHECK(off <= relative);
}

TEST_CASE("Rayleigh damping by modes: refusals name the key") {
  const std::string key = "d.toml:5: model.damping.rayleigh";  // damping on the 5th line
  const auto says = [&](const std::string& damping, const std::string& part) {
    const std::string message = refusal(with_damping(damping));
    CAPTURE(message);
    CHECK(message.find(part) != std::string::npos);
  };
  says("{ rayleigh = { modes = [1, 1], ratios = [0.05, 0.05] } }",
       key + ".modes: the two modes must differ");
  says("{ rayleigh = { modes = [0, 2], ratios = [0.05, 0.05] } }",
       key + ".modes[1]: must be a mode number >= 1");
  says("{ rayleigh = { modes = [1.5, 2], ratios = [0.05, 0.05] } }", key + ".modes[1]");
  says("{ rayleigh = { modes = [1], ratios = [0.05, 0.05] } }", key + ".modes: expected two modes");
  says("{ rayleigh = { modes = [1, 6], ratios = [0.05, 0.05] } }",
       key + ": mode 6: the constrained model has 5 modes");
  says("{ rayleigh = { modes = [1, 2], ratios = [0.05, 1.5] } }",
       key + ".ratios[2]: must be a damping ratio in [0, 1)");
  says("{ rayleigh = { modes = [1, 2], frequencies = [1.0, 2.0], ratios = [0.05, 0.05] } }",
       key + ".modes: give either frequencies or modes, not both");
  says("{ rayleigh = { ratios = [0.05, 0.05] } }",
       key + ": expected frequencies = [f1, f2] (cycles per time unit) or modes = [i, j]");
  // A tenfold ratio at the higher mode needs a negative a0.
  says("{ rayleigh = { modes = [1, 5], ratios = [0.001, 0.5] } }", "a negative or infinite");
  // A nonlinear model has no constant modes.
  const std::string pendulum =
      test::replace(test::pendulum_scene("t_end = 1.0\noutput_step = 0.5\n"), "gravity",
                    "damping = { rayleigh = { modes = [1, 2], ratios = [0.05, 0.05] } }\ngravity");
  CHECK(refusal(pendulum).find("Rayleigh damping by modes needs a linear model") !=
        std::string::npos);
}

}  // namespace test_rayleigh_modes
