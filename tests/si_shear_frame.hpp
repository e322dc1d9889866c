#pragma once
// A five-storey shear frame in SI units (issue 10, item 2): floor masses 2.5e3 to 2e4 kg, storey
// stiffnesses 5e5 to 1e7 N/m, a base driven by a prescribed harmonic displacement, a rigid top
// floor tying two DOFs. The scene of test_tolerance_weights.cpp and its validation file.

#include <sstream>
#include <string>

#include "tests/solve_helpers.hpp"

namespace condyn::test {

/// The frame with masses and stiffnesses multiplied by `scale` (1: kg and N/m; 1e-3: t and kN/m,
/// the same model in other units: displacements unchanged, forces times 1e-3).
inline std::string si_shear_frame(double scale, const std::string& extra_solve = "") {
  // DOFs: base, floors 1-4, the top floor's two halves (tied by the rigid-floor MFC).
  const double m[7] = {1e4, 2e4, 1.5e4, 1.2e4, 8e3, 2.5e3, 2.5e3};
  struct Spring {
    int i, j;
    double k;
  };
  const Spring springs[6] = {{0, 1, 1e7}, {1, 2, 8e6}, {2, 3, 5e6},
                             {3, 4, 3e6}, {4, 5, 5e5}, {4, 6, 5e5}};
  double K[7][7] = {};
  for (const Spring& s : springs) {
    K[s.i][s.i] += s.k;
    K[s.j][s.j] += s.k;
    K[s.i][s.j] -= s.k;
    K[s.j][s.i] -= s.k;
  }
  std::ostringstream t;
  t.precision(17);
  t << "[model]\ntype = \"matrix\"\ndofs = [\"ub\", \"u1\", \"u2\", \"u3\", \"u4\", \"u5a\", "
       "\"u5b\"]\nmass = [";
  for (int i = 0; i < 7; ++i) {
    t << (i ? ", " : "") << "[";
    for (int j = 0; j < 7; ++j) t << (j ? ", " : "") << (i == j ? m[i] * scale : 0.0);
    t << "]";
  }
  t << "]\nstiffness = [";
  for (int i = 0; i < 7; ++i) {
    t << (i ? ", " : "") << "[";
    for (int j = 0; j < 7; ++j) t << (j ? ", " : "") << K[i][j] * scale;
    t << "]";
  }
  // Base motion 0.02 sin(8 t) m, so v_b(0) = 0.16 m/s.
  t << "]\n[[constraint]]\nname = \"base\"\nterms = { ub = 1.0 }\n"
       "value = { type = \"harmonic\", amplitude = 0.02, omega = 8.0 }\n"
       "[[constraint]]\nname = \"floor\"\nterms = { u5a = 1.0, u5b = -1.0 }\n"
       "[initial]\nvelocity = { ub = 0.16 }\n"
       "[solve]\nt_end = 2.0\noutput_step = 0.05\n"
    << extra_solve;
  return t.str();
}

inline BuiltScene si_shear_frame_built(double scale, double rtol,
                                       const std::string& extra_solve = "") {
  SceneSpec spec = parse_scene_text(si_shear_frame(scale, extra_solve), "shear frame");
  spec.solve.rtol = rtol;
  return built(spec);
}

}  // namespace condyn::test
