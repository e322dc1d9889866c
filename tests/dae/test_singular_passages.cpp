// Passages near a singular configuration (dae/run/singular_passages.hpp): the conditioning estimate
// against a dense SVD, both passages of the parallelogram four-bar reported without a change of
// branch, and the N-four-bar's change of branch under index2 reported where projection stays.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "dae/run/singular_passages.hpp"
#include "models/core/singular_values.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

namespace test_singular_passages {

namespace {

using condyn::Scheme;
using condyn::SingularPassage;

condyn::test::BuiltScene scene(const std::string& name) {
  return condyn::test::built(
      condyn::parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/" + name));
}

int dof(const condyn::Model& model, const std::string& name) {
  for (std::size_t k = 0; k < model.dof_names.size(); ++k) {
    if (model.dof_names[k] == name) return static_cast<int>(k);
  }
  FAIL("no DOF " << name);
  return -1;
}

/// The parallelogram's displacements with the crank at angle θ (B = (cos θ, sin θ), C = B + (4, 0)
/// against their positions (0, 1) and (4, 1) in the scene).
Eigen::VectorXd parallelogram_at(const condyn::Model& model, double theta) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
  u[dof(model, "ux2")] = u[dof(model, "ux3")] = std::cos(theta);
  u[dof(model, "uy2")] = u[dof(model, "uy3")] = std::sin(theta) - 1.0;
  return u;
}

/// σ_min of the rows as ConstraintConditioning defines them, by a dense SVD.
double dense_conditioning(condyn::MechanicalSystem& system, const Eigen::VectorXd& u) {
  Eigen::MatrixXd A = system.constraint_jacobian(0.0, u);
  const Eigen::VectorXd mass = system.mass(0.0, u).diagonal();
  double lightest = std::numeric_limits<double>::infinity();
  for (double m : mass) {
    if (m > 0.0) lightest = std::min(lightest, m);
  }
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    A.col(j) /= std::sqrt(mass[j] > 0.0 ? mass[j] : lightest);
  }
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.row(i).normalize();
  return condyn::singular_values(A).minCoeff();
}

/// The largest distance over the rows between the displacements of nodes i and j: 0 while the
/// member between them translates (the coupler on the parallelogram branch).
double coupler_turn(const condyn::Model& model, const condyn::Trajectory& traj, int i, int j) {
  const auto row = [&](const std::string& name) { return traj.u.row(dof(model, name)).array(); };
  const std::string ni = std::to_string(i), nj = std::to_string(j);
  const Eigen::ArrayXd dx = row("ux" + nj) - row("ux" + ni);
  const Eigen::ArrayXd dy = row("uy" + nj) - row("uy" + ni);
  return (dx.square() + dy.square()).sqrt().maxCoeff();
}

/// A chain of `links` unit masses on rigid members between two supports `links` apart, sagging
/// by `sag` (node k at (k, −sag sin(π k / links))): taut (sag 0) its rows are dependent.
condyn::test::BuiltScene sagging_chain(int links, double sag) {
  std::ostringstream s;
  s.precision(17);
  s << "[model]\ntype = \"truss2d\"\nnodes = [";
  for (int k = 0; k <= links; ++k) {
    s << (k ? ", " : "") << "[" << k << ".0, " << -sag * std::sin(std::numbers::pi * k / links)
      << "]";
  }
  s << "]\nmasses = [0.0";
  for (int k = 1; k < links; ++k) s << ", 1.0";
  s << ", 0.0]\nsupports = [1, " << links + 1 << "]\nmembers = [";
  for (int k = 1; k <= links; ++k) {
    s << (k > 1 ? ", " : "") << "{ nodes = [" << k << ", " << k + 1 << "], rigid = true }";
  }
  s << "]\n[solve]\nt_end = 1.0\noutput_step = 0.1\n";
  return condyn::test::built(condyn::parse_scene_text(s.str(), "chain.toml"));
}

}  // namespace

TEST_CASE("conditioning: a sagging chain against a dense SVD, dense and sparse Gram matrices") {
  // 10 links: 14 rows (the dense Gram matrix); 70 links: 74 rows (the sparse one).
  for (const int links : {10, 70}) {
    for (const double sag : {0.1, 1e-3}) {
      CAPTURE(links);
      CAPTURE(sag);
      const auto s = sagging_chain(links, sag);
      condyn::ConstraintConditioning conditioning(*s.model.system);
      const auto system = s.model.system->clone();
      const Eigen::VectorXd u = Eigen::VectorXd::Zero(s.model.dofs());
      const double exact = dense_conditioning(*system, u);
      const double roundoff = 64 * std::numeric_limits<double>::epsilon() *
                              std::sqrt(double(s.model.constraint_count()));
      const double estimate = conditioning(0.0, u);
      // The Rayleigh quotient bounds σ_min from above; near singular (the smallest eigenvalue
      // of Â Âᵀ far below the next) it converges to it.
      CHECK(estimate >= exact - roundoff);
      if (sag < 1e-2) CHECK(estimate <= exact * (1 + 1e-9) + roundoff);
    }
  }
  // Pulled taut (every node on the line of the supports, whatever the members' lengths): the
  // rows are dependent. A scene cannot start there (the build refuses a singular start).
  const auto chain = sagging_chain(70, 0.1);
  Eigen::VectorXd taut = Eigen::VectorXd::Zero(chain.model.dofs());
  for (int k = 1; k < 70; ++k) {
    taut[dof(chain.model, "uy" + std::to_string(k + 1))] =
        0.1 * std::sin(std::numbers::pi * k / 70);
  }
  condyn::ConstraintConditioning conditioning(*chain.model.system);
  CHECK(conditioning(0.0, taut) < 1e3 * std::numeric_limits<double>::epsilon());
}

TEST_CASE("conditioning: the parallelogram's rows against a dense SVD, 0 where collinear") {
  const auto s = scene("parallelogram_four_bar.toml");
  condyn::ConstraintConditioning conditioning(*s.model.system);
  const auto system = s.model.system->clone();
  // Unit rows: σ_max ≤ √m; both computations err by a few ulps of it.
  const double roundoff = 64 * std::numeric_limits<double>::epsilon() * std::sqrt(7.0);
  for (const double phi : {1e-2, 1e-4, 1e-7}) {
    CAPTURE(phi);
    const Eigen::VectorXd u = parallelogram_at(s.model, std::numbers::pi + phi);
    const double exact = dense_conditioning(*system, u);
    // Near singular the smallest eigenvalue of Â Âᵀ is far below the next (σ_min ≈ φ/2 here,
    // σ_2 ≈ 0.5): three inverse iterations converge to roundoff.
    CHECK(std::abs(conditioning(0.0, u) - exact) <= roundoff + 1e-9 * exact);
    CHECK(exact < SingularPassage::kNearSingular);
  }
  // On the collinear line itself the rows are dependent.
  CHECK(conditioning(0.0, parallelogram_at(s.model, std::numbers::pi)) <= roundoff);
  // Upright, far from it: the Rayleigh quotient bounds σ_min from above.
  const Eigen::VectorXd upright = parallelogram_at(s.model, std::numbers::pi / 2);
  CHECK(conditioning(0.0, upright) >= dense_conditioning(*system, upright) - roundoff);
  CHECK(conditioning(0.0, upright) > SingularPassage::kNearSingular);
}

TEST_CASE("the parallelogram's two collinear passages: reported, rows flagged, branch changes") {
  // The schemes' own steps through the passages ([solve] bridge_singular = false), which the
  // monitor judges; bridged, the next case.
  auto s = scene("parallelogram_four_bar.toml");
  s.spec.solve.bridge_singular = false;
  // ω = π/2 rad/s: collinear at t = 1 and t = 3. σ ≈ φ/2 (previous case), so the passage is
  // |ω (t - t*)| < 2 kNearSingular: 0.064 s either side.
  const double half_width = 2 * SingularPassage::kNearSingular / (std::numbers::pi / 2);
  // The coupler's ends B (node 2) and C (node 3) apart: on the crossed branch they end 2 apart;
  // on the parallelogram they stay together to the run's tolerance (observed below 4e-12).
  constexpr double kTurned = 0.5, kTranslates = 1e-6;
  for (const Scheme scheme :
       {Scheme::index1, Scheme::baumgarte, Scheme::index2, Scheme::ggl, Scheme::projection}) {
    CAPTURE(scheme);
    const auto result = condyn::test::solved(s.model, condyn::test::under(s.spec.solve, scheme));
    const auto& passages = result.summary.singular_passages;
    REQUIRE(passages.size() == 2);
    for (std::size_t k = 0; k < 2; ++k) {
      const SingularPassage& p = passages[k];
      const double t_star = k == 0 ? 1.0 : 3.0;
      CAPTURE(t_star);
      CHECK(p.t_enter < t_star);
      CHECK(p.t_leave > t_star);
      // One step either side of the passage's edge (projection's steps here reach 0.03 s, the
      // DAE schemes' stay below 0.01 s).
      constexpr double kStep = 0.04;
      CHECK(p.t_enter > t_star - half_width - kStep);
      CHECK(p.t_leave < t_star + half_width + kStep);
      // The closest step lies within half a step of t*, where σ ≈ ω |t − t*| / 2.
      CHECK(p.closest < std::numbers::pi / 4 * kStep / 2);
      CHECK_FALSE(p.left_open);
    }
    // What each scheme did at t = 3 (index1, Baumgarte and index2 take the crossed branch, as
    // docs/limitations.md described it), and what the monitor says.
    const double turn = coupler_turn(s.model, result.trajectory, 2, 3);
    const bool left =
        scheme == Scheme::index1 || scheme == Scheme::baumgarte || scheme == Scheme::index2;
    CHECK(turn > (left ? kTurned : 0.0));
    if (!left) CHECK(turn < kTranslates);
    CHECK_FALSE(passages[0].left_branch());
    CHECK(passages[1].left_branch() == left);
    CHECK(condyn::singular_passage_warnings(passages).size() == (left ? 1U : 0U));
    const auto near = condyn::near_singular_rows(passages, result.trajectory.t);
    for (std::size_t k = 0; k < near.size(); ++k) {
      const double t = result.trajectory.t[k];
      CHECK_MESSAGE(near[k] == (std::abs(t - 1.0) < 1e-9 || std::abs(t - 3.0) < 1e-9), t);
    }
    CHECK(result.summary.notes_text().find("passed 2 near-singular configurations") !=
          std::string::npos);
  }
}

TEST_CASE("bridged, every BDF scheme holds the parallelogram's branch through both passages") {
  // dae/integrators/passage_bridge.hpp: generalized-α steps from where the conditioning falls
  // below kNearSingular of its best to where it has recovered (kExitGrowth, exit_fraction). The
  // coupler's ends stay together to the bridge's accuracy (observed below 2e-7 under every scheme
  // at the scene's rtol 1e-8), against the 2 apart of the crossed branch.
  const auto s = scene("parallelogram_four_bar.toml");
  constexpr double kTranslates = 1e-5;
  for (const Scheme scheme : {Scheme::index1, Scheme::baumgarte, Scheme::index2, Scheme::index3,
                              Scheme::ggl, Scheme::projection}) {
    CAPTURE(scheme);
    const auto result = condyn::test::solved(s.model, condyn::test::under(s.spec.solve, scheme));
    CHECK(coupler_turn(s.model, result.trajectory, 2, 3) < kTranslates);
    const auto& passages = result.summary.singular_passages;
    REQUIRE(passages.size() == 2);
    CHECK_FALSE(passages[0].left_branch());
    CHECK_FALSE(passages[1].left_branch());
    CHECK(result.summary.notes_text().find("bridged 2 near-singular configurations") !=
          std::string::npos);
  }
}

TEST_CASE("N-four-bar: index2 leaving the parallelogram branch is reported, projection stays") {
  auto s = scene("n_four_bar.toml");
  s.spec.solve.t_end = 1.5;              // past the first horizontal crossings
  s.spec.solve.bridge_singular = false;  // the schemes' own steps, which the monitor judges
  const auto index2 =
      condyn::test::solved(s.model, condyn::test::under(s.spec.solve, Scheme::index2));
  // What the run did: the coupler turned (B1 and B0 apart by up to the 2 of the other branch).
  CHECK(coupler_turn(s.model, index2.trajectory, 2, 4) > 0.5);
  int left = 0;
  for (const SingularPassage& p : index2.summary.singular_passages) left += p.left_branch() ? 1 : 0;
  CHECK(left >= 1);
  CHECK_FALSE(condyn::singular_passage_warnings(index2.summary.singular_passages).empty());

  const auto projection =
      condyn::test::solved(s.model, condyn::test::under(s.spec.solve, Scheme::projection));
  // On the branch: the coupler translates to the projection's roundoff.
  CHECK(coupler_turn(s.model, projection.trajectory, 2, 4) < 1e-9);
  REQUIRE_FALSE(projection.summary.singular_passages.empty());
  for (const SingularPassage& p : projection.summary.singular_passages) {
    CHECK_FALSE(p.left_branch());
  }
  CHECK(condyn::singular_passage_warnings(projection.summary.singular_passages).empty());
}

TEST_CASE("a linear model has no singular passages to report") {
  const auto s = scene("truss_inclined_roller.toml");
  const auto result = condyn::test::solved(s.model, s.spec.solve);
  CHECK(result.summary.singular_passages.empty());
  CHECK(result.summary.notes_text().find("near-singular") == std::string::npos);
}

TEST_CASE("a long chain, ill-conditioned by its length alone, passes no singular configuration") {
  // 300 links in a line at 30°: σ about π/600 in any configuration near it (5e-3, below
  // kNearSingular itself), with no change of rank anywhere; the passage threshold is relative to
  // the run's best conditioning, so nothing is reported (the absolute one reported a passage
  // "ended inside" for every chain of more than some 30 links).
  const auto s = condyn::test::built(condyn::parse_scene_text(
      condyn::test::replace(condyn::test::hanging_chain_scene(300),
                            "t_end = 1.0\noutput_step = 0.1", "t_end = 0.05\noutput_step = 0.05"),
      "chain.toml"));
  condyn::ConstraintConditioning conditioning(*s.model.system);
  const double sigma0 = conditioning(0.0, Eigen::VectorXd::Zero(s.model.dofs()));
  CHECK(sigma0 < SingularPassage::kNearSingular);
  CHECK(sigma0 > 0.5 * std::numbers::pi / 600.0);
  const auto result = condyn::test::solved(s.model, s.spec.solve);
  CHECK(result.summary.singular_passages.empty());
  CHECK(condyn::singular_passage_warnings(result.summary.singular_passages).empty());
}

}  // namespace test_singular_passages
