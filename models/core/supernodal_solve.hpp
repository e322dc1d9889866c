#pragma once
/// x ← A⁻¹ x from a supernodal Cholesky factor L Lᵀ = P A Pᵀ (CHOLMOD's, read in place), its two
/// triangular sweeps split over two lanes (models/core/second_lane.hpp).
///
/// Why not CHOLMOD's own solve: it visits the supernodes one after the other, and on a mesh's
/// factor each visit is a small dense triangular solve and product (OpenBLAS's dtrsv and dgemv,
/// which a second OpenBLAS thread does not speed up), so the solve runs at one core's speed
/// (10 ms a solve on the 10⁵-DOF braced wall, a third of its step: docs/benchmarks.md). The
/// supernodal elimination tree splits instead: below the top separators, two sets of whole
/// subtrees of about equal entries have no supernode in common and are swept at the same time,
/// one per lane; the few supernodes above them (the ancestors of both sets) are swept by the
/// caller alone. In the forward sweep the updates of one lane's supernodes to the shared
/// ancestors' rows go to that lane's own buffer, added in afterwards, so no row is written by both
/// lanes; the backward sweep only reads the ancestors' rows. The order of every sum is fixed by
/// the factor's structure, not by the lanes: one lane or two give the same x bit for bit.

#include <vector>

namespace condyn {

class SecondLane;
/// SecondLane::shared(), for default arguments without the header.
SecondLane& default_lane();

/// A supernodal factor's arrays, as CHOLMOD stores them (cholmod_factor with is_super): supernode
/// s holds columns super[s] … super[s+1]−1; its rows are s_rows[pi[s] … pi[s+1]) (its own columns
/// first, then the rows below, ascending), its values the column-major block at x + px[s] with
/// pi[s+1] − pi[s] rows; perm is P (row k of P A Pᵀ is row perm[k] of A). The supernodes are in a
/// topological order of the elimination tree (children before parents).
struct SupernodalFactorView {
  int n = 0;
  int nsuper = 0;
  const int* super = nullptr;
  const int* pi = nullptr;
  const int* px = nullptr;
  const int* s_rows = nullptr;
  const double* x = nullptr;
  const int* perm = nullptr;
};

class SupernodalSolve {
 public:
  /// The split of `factor`'s supernodes into the two lanes' subtrees and their ancestors; reads
  /// the structure only (the values, factor.x, are read at each solve and may change between
  /// them, the structure may not).
  /// The solves run on `lane` (the process's shared one by default).
  explicit SupernodalSolve(const SupernodalFactorView& factor, SecondLane& lane = default_lane());
  ~SupernodalSolve();
  SupernodalSolve(const SupernodalSolve&) = delete;
  SupernodalSolve& operator=(const SupernodalSolve&) = delete;

  /// x ← A⁻¹ x (x of length n) with the factor's current values.
  void solve_in_place(double* x);
  /// The values' address, after a refactorization that moved them.
  void set_values(const double* x) { factor_.x = x; }
  /// The share of the factor's entries in the supernodes the caller sweeps alone (the ancestors
  /// of both lanes' subtrees), and the larger lane's share of the rest: how well the split pays.
  [[nodiscard]] double shared_share() const { return shared_share_; }
  [[nodiscard]] double larger_lane_share() const { return larger_lane_share_; }
  /// Lanes the solves run on (1 or 2, SecondLane::lanes()).
  [[nodiscard]] int lanes() const;

 private:
  void forward(int sn, double* y, double* shared_rows, int first_shared_row, double* work) const;
  void backward(int sn, double* y, double* work) const;

  SupernodalFactorView factor_;
  /// Supernodes of each lane and of their common ancestors, in the factor's order.
  std::vector<int> lane_[2];
  std::vector<int> shared_;
  /// For lane 1's supernodes: the first column past their subtree's root (rows from it on belong
  /// to the shared ancestors and are accumulated in shared_rows_).
  std::vector<int> subtree_end_;
  std::vector<int> shared_columns_;
  std::vector<double> y_, shared_rows_, work_[2];
  double shared_share_ = 0.0, larger_lane_share_ = 0.0;
  SecondLane* lane_runner_;
};

}  // namespace condyn
