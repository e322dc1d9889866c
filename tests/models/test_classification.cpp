// Constraint classification (models/core/classification.hpp): the classes of a mixed scene of
// linear and nonlinear rows, and its cost: `info` classified every nonlinear row with a clone of
// the whole system and full evaluations of A and the residuals, quadratic in the rows (issue 42;
// docs/benchmarks.md).
#include <doctest/doctest.h>

#include <memory>
#include <string>
#include <vector>

#include "models/core/classification.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_classification {

namespace {

/// How often the system was cloned and evaluated, over all its clones.
struct Counts {
  int clones = 0, jacobians = 0, residuals = 0;
};

/// A system that forwards to another and counts the calls classification makes.
class CountingSystem final : public MechanicalSystem {
 public:
  CountingSystem(std::unique_ptr<MechanicalSystem> inner, std::shared_ptr<Counts> counts)
      : inner_(std::move(inner)), counts_(std::move(counts)) {}

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    ++counts_->clones;
    return std::make_unique<CountingSystem>(inner_->clone(), counts_);
  }
  [[nodiscard]] int dofs() const override { return inner_->dofs(); }
  [[nodiscard]] int constraints() const override { return inner_->constraints(); }
  [[nodiscard]] const std::vector<bool>& position_rows() const override {
    return inner_->position_rows();
  }
  [[nodiscard]] const Sparse& mass(double t, ConstRef u) override { return inner_->mass(t, u); }
  void force(double t, ConstRef u, ConstRef v, Ref f) override { inner_->force(t, u, v, f); }
  [[nodiscard]] const Sparse& stiffness(double t, ConstRef u, ConstRef v) override {
    return inner_->stiffness(t, u, v);
  }
  [[nodiscard]] const Sparse& damping(double t, ConstRef u, ConstRef v) override {
    return inner_->damping(t, u, v);
  }
  [[nodiscard]] const Sparse& constraint_jacobian(double t, ConstRef u) override {
    ++counts_->jacobians;
    return inner_->constraint_jacobian(t, u);
  }
  void position_residual(double t, ConstRef u, Ref phi) override {
    ++counts_->residuals;
    inner_->position_residual(t, u, phi);
  }
  void velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) override {
    ++counts_->residuals;
    inner_->velocity_residual(t, u, v, psi);
  }
  void acceleration_bias(double t, ConstRef u, ConstRef v, Ref gamma) override {
    inner_->acceleration_bias(t, u, v, gamma);
  }
  [[nodiscard]] bool has_curvature() const override { return inner_->has_curvature(); }
  [[nodiscard]] const Sparse& constraint_force_jacobian(double t, ConstRef u, ConstRef w) override {
    ++counts_->jacobians;
    return inner_->constraint_force_jacobian(t, u, w);
  }

 private:
  std::unique_ptr<MechanicalSystem> inner_;
  std::shared_ptr<Counts> counts_;
};

/// The model with its system wrapped so that calls are counted in `counts`.
Model counted(Model model, const std::shared_ptr<Counts>& counts) {
  model.system = std::make_shared<CountingSystem>(model.system->clone(), counts);
  return model;
}

std::string row_text(const ConstraintClass& c) {
  std::string s = c.name + ": " + (c.single_freedom ? "SFC " : "MFC ") + c.holonomy() +
                  (c.rheonomic ? " rheonomic" : " scleronomic") +
                  (c.homogeneous ? " homogeneous" : " nonhomogeneous") +
                  (c.linear ? " linear" : " nonlinear") + " [";
  for (const auto& d : c.dofs) s += d + " ";
  return s + "]";
}

std::string joined(const std::vector<std::string>& rows) {
  std::string s;
  for (const auto& r : rows) s += r + "\n";
  return s;
}

}  // namespace

TEST_CASE("classification of a mixed scene: linear and nonlinear, scleronomic and rheonomic") {
  // A three-link chain (rigid members 1-2, 2-3, 3-4 from the support at node 1) with a linear
  // tie of node 3 to node 2 driven in time (0.01 t², so the rest state is consistent), and a
  // linear support of ux4 alone; the car axis's road row
  // (xb(t) xl + yb(t) yl = 0, rheonomic; at t = 0, where A is probed, yb = r sin(ω 0) = 0, so
  // the row touches xl alone) beside its axle (|l − r|² = L², scleronomic). The
  // classes follow from the rows as written (Tables 5.1 and 5.2); the per-row classification
  // this replaced gave the same.
  const std::string truss = test::hanging_chain_scene(3) + R"([[constraint]]
name = "tie"
terms = { uy3 = 1.0, uy2 = -1.0 }
value = { type = "polynomial", coefficients = [0.0, 0.0, 0.01] }
[[constraint]]
name = "rail"
terms = { ux4 = 1.0 }
)";
  const auto chain = test::built(parse_scene_text(truss, "mixed.toml"));
  std::vector<std::string> got;
  for (const auto& c : classify_constraints(chain.model, chain.spec.solve.t_end)) {
    got.push_back(row_text(c));
  }
  const std::vector<std::string> chain_expected = {
      "fix_ux1: SFC holonomic scleronomic homogeneous linear [ux1 ]",
      "fix_uy1: SFC holonomic scleronomic homogeneous linear [uy1 ]",
      "tie: MFC holonomic rheonomic nonhomogeneous linear [uy2 uy3 ]",
      "rail: SFC holonomic scleronomic homogeneous linear [ux4 ]",
      "rigid_1_2: MFC holonomic scleronomic homogeneous nonlinear [ux1 uy1 ux2 uy2 ]",
      "rigid_2_3: MFC holonomic scleronomic homogeneous nonlinear [ux2 uy2 ux3 uy3 ]",
      "rigid_3_4: MFC holonomic scleronomic homogeneous nonlinear [ux3 uy3 ux4 uy4 ]"};
  CHECK_MESSAGE(got == chain_expected, joined(got));

  const auto car = test::built(parse_scene_file(std::string(CONDYN_SOURCE_DIR) +
                                                "/validation/scenes/benchmark_car_axis.toml"));
  got.clear();
  for (const auto& c : classify_constraints(car.model, 3.0)) got.push_back(row_text(c));
  const std::vector<std::string> car_expected = {
      "road: SFC holonomic rheonomic nonhomogeneous nonlinear [xl ]",
      "axle: MFC holonomic scleronomic homogeneous nonlinear [xl yl xr yr ]"};
  CHECK_MESSAGE(got == car_expected, joined(got));
}

TEST_CASE("classification costs one clone and a fixed number of evaluations, whatever the rows") {
  // 300 rigid links: the per-row classification cloned the system 300 times and evaluated A
  // 4 times per row (1,200 evaluations of a 300-row A: quadratic). Now one clone, A at four
  // states, and each residual at two times, for all rows together.
  constexpr int kLinks = 300;
  const auto chain = test::built(parse_scene_text(test::hanging_chain_scene(kLinks), "c.toml"));
  const auto counts = std::make_shared<Counts>();
  const Model model = counted(chain.model, counts);
  const auto classes = classify_constraints(model, chain.spec.solve.t_end);
  REQUIRE(classes.size() == static_cast<std::size_t>(kLinks + 2));  // two support rows
  CHECK(counts->clones == 1);
  CHECK(counts->jacobians == 4);
  CHECK(counts->residuals == 4);
  // And every rod row still has its four DOFs.
  for (std::size_t i = 2; i < classes.size(); ++i) {
    CAPTURE(classes[i].name);
    CHECK(classes[i].dofs.size() == 4);
    CHECK_FALSE(classes[i].linear);
  }

  // The sleigh's one velocity row adds its Frobenius test: A and ∂(Aᵀw)/∂u once more.
  const auto sleigh = test::built(
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/chaplygin_sleigh.toml"));
  const auto sleigh_counts = std::make_shared<Counts>();
  (void)classify_constraints(counted(sleigh.model, sleigh_counts), sleigh.spec.solve.t_end);
  CHECK(sleigh_counts->clones == 1);
  CHECK(sleigh_counts->jacobians == 4 + 2);
}

}  // namespace test_classification
