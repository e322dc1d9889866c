// The exact modal reference on inputs of real-size scenes: a [[load]] pattern (one sparse vector
// over many DOFs) and a model too large for the dense modal solution.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "validation/references/exact_solution.hpp"

using namespace condyn;

namespace test_exact_solution_inputs {

namespace {

const std::string kChain = R"(
[model]
type = "matrix"
dofs = ["u1", "u2", "u3"]
mass = [[1.0, 0, 0], [0, 2.0, 0], [0, 0, 1.5]]
stiffness = [[2.0, -1.0, 0], [-1.0, 2.0, -1.0], [0, -1.0, 1.0]]
[[constraint]]
terms = { u1 = 1.0, u3 = -1.0 }
)";
const std::string kSolve = "[solve]\nt_end = 1.0\noutput_step = 0.25\n";

}  // namespace

TEST_CASE("exact solution: a load pattern acts as the same loads written per DOF") {
  // f(t) = (0.5, 0, -2) step(t) as one pattern, and as two point loads.
  test::Sandbox box;
  (void)box.write("f.mtx",
                  "%%MatrixMarket matrix coordinate real general\n3 1 2\n1 1 0.5\n3 1 -2.0\n");
  const std::string step = "value = { type = \"step\", amplitude = 1.0 }\n";
  const Model pattern = build_model(parse_scene_file(
      box.write("p.toml", kChain + "[[load]]\npattern = { file = \"f.mtx\" }\n" + step + kSolve)
          .string()));
  const Model points = build_model(parse_scene_text(
      kChain + "[[load]]\ndof = \"u1\"\nvalue = { type = \"step\", amplitude = 0.5 }\n" +
          "[[load]]\ndof = \"u3\"\nvalue = { type = \"step\", amplitude = -2.0 }\n" + kSolve,
      "points.toml"));
  const std::vector<double> times = {0.0, 0.25, 0.5, 1.0};
  const Trajectory a = exact_trajectory(pattern, times), b = exact_trajectory(points, times);
  // The same modal sums, in another order of addition: a few ulps of the largest displacement.
  CHECK((a.u - b.u).cwiseAbs().maxCoeff() <= 64 * 2.2e-16 * b.u.cwiseAbs().maxCoeff());
  CHECK(b.u.cwiseAbs().maxCoeff() > 0.0);  // the loads move the chain
}

TEST_CASE("exact solution: a model beyond the dense limit is declined with the reason") {
  // kMaxExactDofs + 1 unconstrained unit masses on unit springs to the ground (a diagonal model).
  const int n = kMaxExactDofs + 1;
  std::string dofs, mass, stiffness;
  test::Sandbox box;
  std::string diag = "%%MatrixMarket matrix coordinate real symmetric\n" + std::to_string(n) + " " +
                     std::to_string(n) + " " + std::to_string(n) + "\n";
  for (int i = 1; i <= n; ++i) diag += std::to_string(i) + " " + std::to_string(i) + " 1.0\n";
  (void)box.write("I.mtx", diag);
  const Model model = build_model(parse_scene_file(
      box.write("big.toml",
                "[model]\ntype = \"matrix\"\nmass = { file = \"I.mtx\" }\nstiffness = { file = "
                "\"I.mtx\" }\n" +
                    kSolve)
          .string()));
  CHECK_THROWS_WITH_AS((void)exact_trajectory(model, {0.0, 1.0}),
                       doctest::Contains("2001 DOFs: the modal solution is dense"),
                       ExactSolutionUnavailable);
}

TEST_CASE("exact solution: a slow velocity drive's response, with no terms of size 1/omega") {
  // a' = sin(ωt) on a free mass a tied by a unit spring to a unit mass b: a = (1 − cos ωt)/ω and
  // b'' + b = a, b(0) = b'(0) = 0. For ωt ≪ 1, a = ωt²/2 − ω³t⁴/24 and b is the response to
  // those two terms, (ω/2)(t² − 2 + 2 cos t) − (ω³/24)(t⁴ − 12t² + 24 − 24 cos t), to 1e-16
  // relative (the next terms are ω⁴t⁴ smaller). Written as the responses to A/ω sin(ωt − π/2)
  // and to the constant A/ω, the reference cancelled terms of 1e9 (0.98 relative error at
  // ω = 1e-9); the response to the integral is a divided difference over {0, iω, s1, s2}.
  for (const std::string omega : {"1e-5", "1e-9", "-1e-9", "1e-300"}) {
    CAPTURE(omega);
    const SceneSpec spec = parse_scene_text(std::string(R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[1.0, -1.0], [-1.0, 1.0]]
[[constraint]]
name = "drive"
level = "velocity"
terms = { a = 1.0 }
value = { type = "harmonic", amplitude = 1.0, omega = )") +
                                                omega + R"( }
[solve]
t_end = 10.0
output_step = 1.0
)",
                                            "slow.toml");
    const Model model = build_model(spec);
    const double w = std::stod(omega);
    std::vector<double> times;
    for (int k = 0; k <= 10; ++k) times.push_back(k);
    const Trajectory exact = exact_trajectory(model, times);
    for (std::size_t k = 0; k < times.size(); ++k) {
      const double t = times[k];
      CAPTURE(t);
      const auto col = static_cast<Eigen::Index>(k);
      const double a = w * t * t / 2 - w * w * w * t * t * t * t / 24;
      const double b = (w / 2) * (t * t - 2 + 2 * std::cos(t)) -
                       (w * w * w / 24) * (t * t * t * t - 12 * t * t + 24 - 24 * std::cos(t));
      // a is the integrated time function itself: a few ulps. b comes from the complex response,
      // whose imaginary part (the sine's, of size ωt²/2) carries the roundoff of its real part
      // (the cosine's, t²/2): 64 eps t² absolute (observed 1.6e-16 at t = 10), which is relative
      // 1e-14 at ω = 1e-5 but only 1e-7 at ω = 1e-9, far below what a run at atol 1e-12 reaches.
      CHECK(std::abs(exact.u(0, col) - a) <=
            8 * std::numeric_limits<double>::epsilon() * std::abs(a));
      CHECK(std::abs(exact.u(1, col) - b) <= 64 * std::numeric_limits<double>::epsilon() * t * t);
    }
  }
}

}  // namespace test_exact_solution_inputs
