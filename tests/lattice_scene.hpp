#pragma once
// A truss lattice scene for tests of real-size behaviour (sparse checks, sparse elimination).

#include <string>

namespace condyn::test {

/// A truss2d lattice of nx × ny nodes at unit spacing (square cells with one diagonal), unit
/// masses, its left column supported, and `extra` appended (constraints; [solve] keys after).
inline std::string lattice(int nx, int ny, const std::string& extra,
                           const std::string& solve_keys) {
  const auto id = [nx](int i, int j) { return j * nx + i + 1; };
  std::string nodes, masses, members, supports;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const bool first = i == 0 && j == 0;
      nodes +=
          std::string(first ? "[" : ", [") + std::to_string(i) + ".0, " + std::to_string(j) + ".0]";
      masses += first ? "1.0" : ", 1.0";
      const auto bar = [&members](int a, int b) {
        members += std::string(members.empty() ? "" : ", ") + "{ nodes = [" + std::to_string(a) +
                   ", " + std::to_string(b) + "], EA = 1.0 }";
      };
      if (i + 1 < nx) bar(id(i, j), id(i + 1, j));
      if (j + 1 < ny) bar(id(i, j), id(i, j + 1));
      if (i + 1 < nx && j + 1 < ny) bar(id(i, j), id(i + 1, j + 1));
    }
    supports += std::string(j ? ", " : "") + std::to_string(id(0, j));
  }
  return "[model]\ntype = \"truss2d\"\nnodes = [" + nodes + "]\nmasses = [" + masses +
         "]\nmembers = [" + members + "]\nsupports = [" + supports + "]\n" + extra +
         "[solve]\nt_end = 1.0\noutput_step = 0.1\n" + solve_keys;
}

}  // namespace condyn::test
