#pragma once
/// L X R for sparse X whose pattern does not change between calls (every block a MechanicalSystem
/// reports: models/core/mechanical_system.hpp), with L and R constant: the product's pattern and
/// the list of contributions L_ik X_kl R_lj are made once, and each call refills the values in
/// O(contributions), without allocating. The reduced system of the mixed treatment
/// (dae/formulations/eliminated_system.hpp) maps every block it evaluates so, several times per
/// residual: Eigen's general product would allocate and recompute the pattern each time.

#include <Eigen/Sparse>
#include <vector>

namespace condyn {

class FixedProduct {
 public:
  using Sparse = Eigen::SparseMatrix<double>;

  FixedProduct() = default;
  FixedProduct(const Sparse& left, const Sparse& right);

  /// L X R. Its pattern is the structural product of the three patterns (numerical zeros kept).
  /// When X's pattern differs from the previous call's, the plan is made again.
  const Sparse& operator()(const Sparse& x);

 private:
  void plan(const Sparse& x);

  Sparse left_;                                         ///< L, column-major: column k holds L_ik
  Eigen::SparseMatrix<double, Eigen::RowMajor> right_;  ///< R, row-major: row l holds R_lj
  Sparse result_;
  std::vector<Eigen::Index> outer_, inner_;  ///< X's pattern the plan was made for
  struct Term {
    Eigen::Index dest, src;
    double weight;
  };
  std::vector<Term> terms_;
};

}  // namespace condyn
