#pragma once
// A fixed-free chain of masses and springs with distinct frequencies and a clustered top: the hard
// case for Lanczos (dae/formulations/largest_frequency.hpp).

#include <Eigen/Sparse>
#include <cmath>
#include <vector>

namespace condyn::test {

/// n masses m_i = 1 + 0.5 sin(i) and springs k_i = 1 + 0.3 cos(2i), the first to the ground.
inline void spring_chain(int n, Eigen::SparseMatrix<double>& K, Eigen::SparseMatrix<double>& M) {
  std::vector<Eigen::Triplet<double>> k, m;
  for (int i = 0; i < n; ++i) {
    m.emplace_back(i, i, 1.0 + 0.5 * std::sin(i));
    const double below = 1.0 + 0.3 * std::cos(2.0 * i);  // spring to i-1 (or the ground)
    k.emplace_back(i, i, below);
    if (i > 0) {
      k.emplace_back(i - 1, i - 1, below);
      k.emplace_back(i - 1, i, -below);
      k.emplace_back(i, i - 1, -below);
    }
  }
  K.resize(n, n);
  M.resize(n, n);
  K.setFromTriplets(k.begin(), k.end());
  M.setFromTriplets(m.begin(), m.end());
}

}  // namespace condyn::test
