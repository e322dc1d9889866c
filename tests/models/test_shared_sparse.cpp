// One stiffness matrix for the model and its linear system (models/core/shared_sparse.hpp, issue
// 12).

#include <doctest/doctest.h>

#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_shared_sparse {

TEST_CASE("SharedSparse: readers share one matrix, edit() copies a shared one first") {
  SharedSparse a;
  a.edit().resize(2, 2);
  a.edit().insert(0, 0) = 3.0;
  const auto held = a.share();
  CHECK(held.get() == &*a);  // the same matrix, not a copy
  // Editing while another reader holds it changes this object's copy only.
  a.edit().coeffRef(0, 0) = 5.0;
  CHECK(held->coeff(0, 0) == 3.0);
  CHECK(a->coeff(0, 0) == 5.0);
  CHECK(held.get() != &*a);
  // A copied holder shares until it edits.
  const SharedSparse b = a;
  CHECK(&*b == &*a);
}

TEST_CASE("a linear model's system evaluates the model's own K, not a copy") {
  const auto scene = test::built(parse_scene_text(test::kTwoMassesScene, "two.toml"));
  const Model& model = scene.model;
  REQUIRE_FALSE(model.is_nonlinear());
  const auto system = model.evaluator();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(2);
  const auto& K = system->stiffness(0.0, zero, zero);
  CHECK(&K == &*model.K);
  // With the structural sign: f = loads − K u − C u' (K = [3 −1; −1 1]; the unit step on the
  // second DOF is on at t = 1).
  Eigen::VectorXd f(2);
  system->force(1.0, Eigen::Vector2d(1.0, 2.0), zero, f);
  CHECK(f[0] == -(3.0 * 1.0 - 1.0 * 2.0));
  CHECK(f[1] == 1.0 - (-1.0 * 1.0 + 1.0 * 2.0));
}

}  // namespace test_shared_sparse
