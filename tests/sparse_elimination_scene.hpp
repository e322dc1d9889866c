#pragma once
// The tied lattice of the sparse elimination tests.

#include <string>

#include "tests/lattice_scene.hpp"

namespace condyn::test {

/// Ties in every tenth column of an n x n lattice (100 x 100 by default: 20,000 DOFs): uy of the
/// column's top node equals uy of its bottom node (one MFC over two DOFs each), and a step load
/// pulling the far corner down.
inline std::string tied_lattice(const std::string& solve_keys, int n = 100) {
  std::string extra;
  for (int i = 10; i < n; i += 10) {
    const int bottom = i + 1, top = (n - 1) * n + i + 1;
    extra += "[[constraint]]\nname = \"tie" + std::to_string(i) + "\"\nterms = { uy" +
             std::to_string(top) + " = 1.0, uy" + std::to_string(bottom) + " = -1.0 }\n";
  }
  extra += "[[load]]\ndof = \"uy" + std::to_string(n * n) +
           "\"\nvalue = { type = \"step\", amplitude = -1.0 }\n";
  return lattice(n, n, extra, solve_keys);
}

}  // namespace condyn::test
