// Rayleigh damping naming modes, damping = { rayleigh = { modes = [i, j], ratios = [z1, z2] } }
// (models/assembly/modal_damping.cpp): the two modes get their ratios, the coefficients are those
// the same frequencies give, and the refusals name the key.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "dae/formulations/natural_modes.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/shear_building.hpp"

using namespace condyn;
using condyn::test::ShearBuilding;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// A mode's ratio φᵀCφ / (2ω) from mass-normalized shapes: a few roundings of O(1) sums and the
// dense eigensolver's few eps on ω²; 64 eps relative (observed 1.3 eps; the two Cs differ by 1.1
// eps).
constexpr double kRatioTolerance = 64 * kEps;

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
