// The exact modal reference on inputs of real-size scenes: a [[load]] pattern (one sparse vector
// over many DOFs) and a model too large for the dense modal solution.

#include <doctest/doctest.h>

#include <string>

#include "models/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "validation/exact_solution.hpp"

using namespace condyn;

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
