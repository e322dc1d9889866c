#pragma once
// A uniform shear building as a matrix scene, and the closed form of its frequencies (the modes
// tests: tests/dae/test_natural_modes.cpp, tests/src/test_cli_modes.cpp).
//
// n storeys u1..un (u1 at the bottom), each of mass m, joined by storey springs of stiffness k, the
// first to the fixed ground. Its frequencies are
//   ω_j = 2 sqrt(k/m) sin((2j − 1) π / (2 (2n + 1))),  j = 1..n:
// φ_i = sin(i θ) meets every interior row, m ω² φ_i = k (2 φ_i − φ_{i−1} − φ_{i+1}), with
// ω² = 2 (k/m)(1 − cos θ) = 4 (k/m) sin²(θ/2), and φ_0 = 0 at the ground; the top row
// m ω² φ_n = k (φ_n − φ_{n−1}) asks φ_{n+1} = φ_n, sin((n+1)θ) = sin(nθ), so (2n+1) θ / 2 =
// (2j − 1) π / 2. (The eigenvalues of the tridiagonal matrix with one corner changed: W.-C. Yueh,
// "Eigenvalues of several tridiagonal matrices", Applied Mathematics E-Notes 5 (2005) 66-74.)

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace condyn::test {

struct ShearBuilding {
  int storeys = 3;
  double mass = 1.0, stiffness = 1.0;
  /// A DOF u0 for the base, of mass `mass`, held by the constraint u0 = 0 (fix_base) instead of
  /// the ground: its mass is a support's, which no mode moves.
  bool base_dof = false;
  /// Each storey spring split into two of 2k in series through a massless DOF h_i: the same storey
  /// stiffness k, with n massless DOFs that stiffness holds.
  bool massless_midpoints = false;
  /// [ground_motion] with influence 1 on every DOF (the base's and the midpoints' included).
  bool ground_motion = false;
  /// A multiplier on every mass: 0 gives a scene without mass.
  double mass_scale = 1.0;
};

/// ω_j of the closed form above, j = 1..n.
inline double shear_building_omega(const ShearBuilding& b, int j) {
  const double pi = 3.14159265358979323846;
  return 2.0 * std::sqrt(b.stiffness / b.mass) *
         std::sin((2.0 * j - 1.0) * pi / (2.0 * (2.0 * b.storeys + 1.0)));
}

/// The scene text: a matrix model (dense rows), t_end 1.
inline std::string shear_building_scene(const ShearBuilding& b) {
  std::vector<std::string> names;
  if (b.base_dof) names.emplace_back("u0");
  for (int i = 1; i <= b.storeys; ++i) {
    if (b.massless_midpoints) names.push_back("h" + std::to_string(i));
    names.push_back("u" + std::to_string(i));
  }
  const auto n = names.size();
  const auto at = [&](const std::string& name) {
    for (std::size_t i = 0; i < n; ++i)
      if (names[i] == name) return static_cast<int>(i);
    return -1;
  };
  std::vector<std::vector<double>> K(n, std::vector<double>(n, 0.0)), M = K;
  const auto spring = [&](int a, int c, double k) {  // a = -1: the ground
    if (a >= 0) K[a][a] += k;
    K[c][c] += k;
    if (a >= 0) {
      K[a][c] -= k;
      K[c][a] -= k;
    }
  };
  for (int i = 1; i <= b.storeys; ++i) {
    const int below = i == 1 ? at("u0") : at("u" + std::to_string(i - 1));
    const int self = at("u" + std::to_string(i));
    if (b.massless_midpoints) {
      const int h = at("h" + std::to_string(i));
      spring(below, h, 2.0 * b.stiffness);
      spring(h, self, 2.0 * b.stiffness);
    } else {
      spring(below, self, b.stiffness);
    }
    M[self][self] = b.mass * b.mass_scale;
  }
  if (b.base_dof) M[0][0] = b.mass * b.mass_scale;
  std::ostringstream s;
  s.precision(17);
  const auto rows = [&](const std::vector<std::vector<double>>& A) {
    s << "[";
    for (std::size_t i = 0; i < n; ++i) {
      s << (i ? ", [" : "[");
      for (std::size_t j = 0; j < n; ++j) s << (j ? ", " : "") << A[i][j];
      s << "]";
    }
    s << "]\n";
  };
  s << "[model]\ntype = \"matrix\"\ndofs = [";
  for (std::size_t i = 0; i < n; ++i) s << (i ? ", " : "") << '"' << names[i] << '"';
  s << "]\nmass = ";
  rows(M);
  s << "stiffness = ";
  rows(K);
  if (b.base_dof) s << "[[constraint]]\nname = \"fix_base\"\nterms = { u0 = 1.0 }\n";
  if (b.ground_motion) {
    s << "[ground_motion]\nacceleration = 1.0\ninfluence = {";
    for (std::size_t i = 0; i < n; ++i) s << (i ? ", " : " ") << names[i] << " = 1.0";
    s << " }\n";
  }
  s << "[solve]\nt_end = 1.0\noutput_step = 0.5\n";
  return s.str();
}

}  // namespace condyn::test
