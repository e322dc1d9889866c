// Issue 13's validation of massless DOFs: a truss whose top-chord nodes have no mass, integrated
// as a DAE by every scheme that applies, against the same truss with those DOFs condensed by
// hand (the Schur complement of K written out as a `matrix` scene and integrated on its own).

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "models/core/eigen_decompositions.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_massless_truss_validation {

namespace {

/// A Warren-type bridge: bottom chord nodes 1-5 (mass 1 each, y = 0), top chord nodes 6-8
/// (no mass, y = 1), pinned at 1, on a roller at 5, uy2 tied to uy4; gravity, a harmonic load
/// on the massless top node 7 and a step on node 3 at t = 0.05.
const std::string kBridge = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [4.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 1.0]]
masses = [1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]
members = [{ nodes = [1, 2], EA = 400.0 }, { nodes = [2, 3], EA = 400.0 }, { nodes = [3, 4], EA = 400.0 },
           { nodes = [4, 5], EA = 400.0 }, { nodes = [6, 7], EA = 300.0 }, { nodes = [7, 8], EA = 300.0 },
           { nodes = [1, 6], EA = 200.0 }, { nodes = [2, 6], EA = 200.0 }, { nodes = [3, 6], EA = 200.0 },
           { nodes = [3, 7], EA = 200.0 }, { nodes = [3, 8], EA = 200.0 }, { nodes = [4, 8], EA = 200.0 },
           { nodes = [5, 8], EA = 200.0 }]
supports = [1]
gravity = [0.0, -9.81]
[[constraint]]
name = "roller"
terms = { uy5 = 1.0 }
[[constraint]]
name = "tie"
terms = { uy2 = 1.0, uy4 = -1.0 }
[[load]]
dof = "uy7"
value = { type = "harmonic", amplitude = -20.0, omega = 5.0 }
[[load]]
dof = "ux3"
value = { type = "step", amplitude = 4.0, start = 0.05 }
[solve]
t_end = 1.5
output_step = 0.05
rtol = 1e-10
atol = 1e-12
)";

std::string number(double x) {
  std::ostringstream s;
  s << std::setprecision(17) << x;
  return s.str();
}

/// The bridge with its massless DOFs h condensed: K̃ = K_rr − K_rh K_hh⁻¹ K_hr on the others r,
/// the harmonic load on uy7 carried to r as −K_rh K_hh⁻¹ e_uy7 times it, gravity and the step
/// as they were; u_h = K_hh⁻¹ (f_h − K_hr u_r) afterwards.
struct Condensed {
  std::string scene;
  std::vector<int> r, h;    ///< DOF indices of the full model
  Eigen::MatrixXd recover;  ///< u_h = recover_u u_r + recover_f sin(5t)
  Eigen::VectorXd recover_f;
};

Condensed condense(const Model& full) {
  Condensed c;
  for (int j = 0; j < full.dofs(); ++j) (full.M.coeff(j, j) == 0.0 ? c.h : c.r).push_back(j);
  const Eigen::MatrixXd K(*full.K), M(full.M);
  const auto block = [](const Eigen::MatrixXd& S, const std::vector<int>& rows,
                        const std::vector<int>& cols) {
    Eigen::MatrixXd B(rows.size(), cols.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < cols.size(); ++j) B(i, j) = S(rows[i], cols[j]);
    return B;
  };
  const Eigen::MatrixXd Khh = block(K, c.h, c.h), Krh = block(K, c.r, c.h);
  Eigen::MatrixXd Kt = block(K, c.r, c.r) - Krh * Khh.fullPivLu().solve(Krh.transpose());
  // Symmetric to roundoff; the scene must be exactly so, and entries of roundoff size are zeros.
  Kt = (0.5 * (Kt + Kt.transpose())).eval();
  const double tiny = 1e-13 * Kt.cwiseAbs().maxCoeff();
  Kt = Kt.unaryExpr([tiny](double x) { return std::abs(x) <= tiny ? 0.0 : x; });
  const int uy7 = full.dof_at("uy7");
  Eigen::VectorXd eh = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(c.h.size()));
  for (std::size_t k = 0; k < c.h.size(); ++k)
    if (c.h[k] == uy7) eh[static_cast<Eigen::Index>(k)] = -20.0;  // the load's amplitude
  const Eigen::VectorXd carried = -Krh * Khh.fullPivLu().solve(eh);
  c.recover = -Khh.fullPivLu().solve(Krh.transpose());
  c.recover_f = Khh.fullPivLu().solve(eh);

  const Eigen::VectorXd gravity = full.applied_forces(0.0);  // before the step
  std::ostringstream s;
  s << "[model]\ntype = \"matrix\"\ndofs = [";
  for (std::size_t i = 0; i < c.r.size(); ++i)
    s << (i ? ", " : "") << '"' << full.dof_names[static_cast<std::size_t>(c.r[i])] << '"';
  s << "]\n";
  for (const auto& [key, S] : {std::pair<const char*, Eigen::MatrixXd>{"mass", block(M, c.r, c.r)},
                               std::pair<const char*, Eigen::MatrixXd>{"stiffness", Kt}}) {
    s << key << " = [";
    for (Eigen::Index i = 0; i < S.rows(); ++i) {
      s << (i ? ", [" : "[");
      for (Eigen::Index j = 0; j < S.cols(); ++j) s << (j ? ", " : "") << number(S(i, j));
      s << "]";
    }
    s << "]\n";
  }
  for (std::size_t i = 0; i < c.r.size(); ++i) {
    const std::string dof = full.dof_names[static_cast<std::size_t>(c.r[i])];
    const auto k = static_cast<Eigen::Index>(i);
    if (gravity[c.r[i]] != 0.0)
      s << "[[load]]\ndof = \"" << dof << "\"\nvalue = " << number(gravity[c.r[i]]) << "\n";
    if (carried[k] != 0.0) {
      s << "[[load]]\ndof = \"" << dof
        << "\"\nvalue = { type = \"harmonic\", amplitude = " << number(carried[k])
        << ", omega = 5.0 }\n";
    }
  }
  s << "[[load]]\ndof = \"ux3\"\nvalue = { type = \"step\", amplitude = 4.0, start = 0.05 }\n"
       "[[constraint]]\nname = \"fix_ux1\"\nterms = { ux1 = 1.0 }\n"
       "[[constraint]]\nname = \"fix_uy1\"\nterms = { uy1 = 1.0 }\n"
       "[[constraint]]\nname = \"roller\"\nterms = { uy5 = 1.0 }\n"
       "[[constraint]]\nname = \"tie\"\nterms = { uy2 = 1.0, uy4 = -1.0 }\n"
       "[solve]\nt_end = 1.5\noutput_step = 0.05\nrtol = 1e-10\natol = 1e-12\n";
  c.scene = s.str();
  return c;
}

}  // namespace

TEST_CASE("a truss with massless nodes agrees with the truss condensed by hand, every scheme") {
  const auto full = test::built(parse_scene_text(kBridge, "bridge.toml"));
  const Condensed c = condense(full.model);
  REQUIRE(c.h.size() == 6);  // ux6 ... uy8
  const auto ref = test::built(parse_scene_text(c.scene, "bridge_condensed.toml"));
  const Trajectory exact =
      test::solved(ref.model, test::under(ref.spec.solve, Scheme::elimination)).trajectory;
  // The reference against itself under GGL: what agreement at this tolerance looks like.
  const Trajectory exact_ggl =
      test::solved(ref.model, test::under(ref.spec.solve, Scheme::ggl)).trajectory;
  const double scale = exact.u.cwiseAbs().maxCoeff();
  REQUIRE(scale > 0.01);
  MESSAGE("condensed reference: ggl vs elimination, max |du| / max |u| = "
          << (exact_ggl.u - exact.u).cwiseAbs().maxCoeff() / scale);
  for (Scheme scheme : {Scheme::elimination, Scheme::index1, Scheme::baumgarte, Scheme::ggl,
                        Scheme::index2, Scheme::index3, Scheme::projection}) {
    const std::string name = to_string(scheme);
    CAPTURE(name);
    const Trajectory d = test::solved(full.model, test::under(full.spec.solve, scheme)).trajectory;
    REQUIRE(d.t.size() == exact.t.size());
    double du = 0.0, dh = 0.0, dr = 0.0;
    for (std::size_t k = 0; k < d.t.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      Eigen::VectorXd ur(static_cast<Eigen::Index>(c.r.size()));
      for (std::size_t i = 0; i < c.r.size(); ++i) {
        const auto row = static_cast<Eigen::Index>(i);
        ur[row] = d.u(c.r[i], col);
        du = std::max(du, std::abs(d.u(c.r[i], col) - exact.u(row, col)));
        dr = std::max(dr, std::abs(d.reaction(c.r[i], col) - exact.reaction(row, col)));
      }
      const Eigen::VectorXd uh = c.recover * ur + c.recover_f * std::sin(5.0 * d.t[k]);
      for (std::size_t i = 0; i < c.h.size(); ++i)
        dh = std::max(dh, std::abs(d.u(c.h[i], col) - uh[static_cast<Eigen::Index>(i)]));
    }
    MESSAGE(name << ": max |du| / max |u| = " << du / scale << ", massless DOFs' rows "
                 << dh / scale << ", reactions " << dr / exact.reaction.cwiseAbs().maxCoeff());
    CHECK(du <= 1e-7 * scale);
    CHECK(dh <= 1e-9 * scale);
    CHECK(dr <= 1e-6 * exact.reaction.cwiseAbs().maxCoeff());
  }
}

}  // namespace test_massless_truss_validation
