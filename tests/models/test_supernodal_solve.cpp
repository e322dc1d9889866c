// condyn's two-lane supernodal solve (models/core/supernodal_solve.hpp) and the worker it runs on
// (models/core/second_lane.hpp): a hand-built factor whose elimination tree and split are known,
// a chain that cannot be split, CHOLMOD's factors of meshes against CHOLMOD's own solve, one lane
// and two giving the same bits.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/fixed_pattern_cholmod.hpp"
#include "models/core/second_lane.hpp"
#include "models/core/supernodal_solve.hpp"
#include "tests/grid_matrix.hpp"

using namespace condyn;

namespace test_supernodal_solve {

using condyn::test::grid_matrix;
using condyn::test::kSolveRoundoff;
using condyn::test::relative_residual;

/// A supernodal factor written out: each supernode's columns and rows below, values filled with
/// a fixed pseudo-random sequence (a diagonal of 2 to 3 keeps L well conditioned).
struct HandFactor {
  std::vector<int> super, pi, px, s_rows, perm;
  std::vector<double> x;
  int n = 0;

  HandFactor(int columns, const std::vector<std::vector<int>>& supernode_rows,
             const std::vector<int>& first_columns)
      : n(columns) {
    super = first_columns;
    super.push_back(columns);
    pi.push_back(0);
    px.push_back(0);
    double seed = 0.1;
    for (std::size_t s = 0; s < supernode_rows.size(); ++s) {
      const int ncol = super[s + 1] - super[s];
      const int nrow = static_cast<int>(supernode_rows[s].size());
      s_rows.insert(s_rows.end(), supernode_rows[s].begin(), supernode_rows[s].end());
      pi.push_back(pi.back() + nrow);
      px.push_back(px.back() + nrow * ncol);
      for (int j = 0; j < ncol; ++j) {
        for (int i = 0; i < nrow; ++i) {
          seed = std::fmod(seed * 7.31 + 0.37, 1.0);
          x.push_back(i < j ? 0.0 : i == j ? 2.0 + seed : seed - 0.5);
        }
      }
    }
    perm.resize(columns);
    std::iota(perm.begin(), perm.end(), 0);
  }
  [[nodiscard]] SupernodalFactorView view() const {
    return {n,
            static_cast<int>(super.size()) - 1,
            super.data(),
            pi.data(),
            px.data(),
            s_rows.data(),
            x.data(),
            perm.data()};
  }
  /// A = Pᵀ L Lᵀ P, dense: A(perm[k], perm[j]) = (L Lᵀ)(k, j).
  [[nodiscard]] Eigen::MatrixXd matrix() const {
    Eigen::MatrixXd l = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t s = 0; s + 1 < super.size(); ++s) {
      const int nrow = pi[s + 1] - pi[s];
      for (int j = super[s]; j < super[s + 1]; ++j) {
        for (int i = 0; i < nrow; ++i) {
          l(s_rows[pi[s] + i], j) = x[px[s] + (j - super[s]) * nrow + i];
        }
      }
    }
    const Eigen::MatrixXd llt = l * l.transpose();
    Eigen::MatrixXd a(n, n);
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < n; ++j) a(perm[k], perm[j]) = llt(k, j);
    }
    return a;
  }
};

/// Two subtrees under a root column: s2 (column 4) over s0 (columns 0–1) and s1 (2–3); s5
/// (column 8) over s3 (5–6) and s4 (7); s6 (column 9) the root. Entries 8, 6, 2, 6, 3, 2, 1.
HandFactor two_subtrees() {
  return HandFactor(10, {{0, 1, 4, 9}, {2, 3, 4}, {4, 9}, {5, 6, 8}, {7, 8, 9}, {8, 9}, {9}},
                    {0, 2, 4, 5, 7, 8, 9});
}

/// x ← A⁻¹ b on a lane of its own with `lanes` lanes.
Eigen::VectorXd solve_with(const SupernodalFactorView& view, const Eigen::VectorXd& b, int lanes) {
  SecondLane lane(lanes);
  SupernodalSolve solve(view, lane);
  CHECK(solve.lanes() == lanes);
  Eigen::VectorXd x = b;
  solve.solve_in_place(x.data());
  return x;
}

Eigen::VectorXd right_side(Eigen::Index n) {
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = std::sin(0.37 * static_cast<double>(i) + 0.1);
  return b;
}

TEST_CASE("the solve splits the elimination tree below its top and solves L Lᵀ exactly") {
  HandFactor f = two_subtrees();
  const SupernodalSolve solve(f.view());
  // The root split leaves 16 entries against 11 (0.59 of them): s2 is split, then s5 (0.56):
  // lanes {s0, s4} and {s1, s3} hold 11 and 12 of 23; s2, s5, s6 (5 of 28) are shared.
  CHECK(solve.larger_lane_share() == doctest::Approx(12.0 / 23.0).epsilon(1e-15));
  CHECK(solve.shared_share() == doctest::Approx(5.0 / 28.0).epsilon(1e-15));
  const Eigen::VectorXd b = right_side(f.n);
  // A permutation moves the rows: the solve gathers and scatters through it.
  for (const std::vector<int>& perm : {std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9},
                                       std::vector<int>{3, 7, 0, 9, 1, 5, 8, 2, 6, 4}}) {
    f.perm = perm;
    const Eigen::MatrixXd a = f.matrix();
    const Eigen::VectorXd expected = a.ldlt().solve(b);
    for (int lanes : {1, 2}) {
      const Eigen::VectorXd x = solve_with(f.view(), b, lanes);
      CHECK((a * x - b).lpNorm<Eigen::Infinity>() <=
            kSolveRoundoff *
                (a.cwiseAbs().rowwise().sum().maxCoeff() * x.lpNorm<Eigen::Infinity>() +
                 b.lpNorm<Eigen::Infinity>()));
      CHECK((x - expected).lpNorm<Eigen::Infinity>() <=
            1e3 * kSolveRoundoff * expected.lpNorm<Eigen::Infinity>());
    }
    CHECK(solve_with(f.view(), b, 1) == solve_with(f.view(), b, 2));
  }
}

TEST_CASE("a chain of supernodes stays whole and is solved on one lane's share") {
  // Each supernode one column, its parent the next: nothing to split below the root.
  const int n = 40;
  std::vector<std::vector<int>> rows;
  std::vector<int> first(n);
  for (int k = 0; k < n; ++k) {
    first[k] = k;
    rows.push_back(k + 1 < n ? std::vector<int>{k, k + 1} : std::vector<int>{k});
  }
  const HandFactor f(n, rows, first);
  const SupernodalSolve solve(f.view());
  CHECK(solve.shared_share() <= 0.2);
  CHECK(solve.larger_lane_share() == 1.0);
  const Eigen::MatrixXd a = f.matrix();
  const Eigen::VectorXd b = right_side(n), x = solve_with(f.view(), b, 2);
  CHECK((x - a.ldlt().solve(b)).lpNorm<Eigen::Infinity>() <=
        1e3 * kSolveRoundoff * x.lpNorm<Eigen::Infinity>());
}

TEST_CASE("on CHOLMOD's supernodal factor of a mesh the two-lane solve agrees with CHOLMOD's") {
  // A 2D and a 3D mesh's pattern, supernodal under CHOLMOD's rule; the solve of the one and of
  // the other FixedPatternCholmod differ only in the order of their sums.
  struct Mesh {
    int nx, ny, nz;
  };
  for (const Mesh mesh : {Mesh{120, 120, 1}, Mesh{20, 20, 20}}) {
    const Eigen::SparseMatrix<double> a = grid_matrix(mesh.nx, mesh.ny, 0.5, mesh.nz);
    FixedPatternCholmod own("nesdis", 0.0, 1.0), theirs("nesdis", 1e300);
    REQUIRE(own.factor(a));
    REQUIRE(theirs.factor(a));
    REQUIRE(own.supernodal());
    CHECK(own.solve_lanes() >= 1);
    CHECK(theirs.solve_lanes() == 0);
    const Eigen::VectorXd b = right_side(a.rows());
    Eigen::VectorXd x = b, y = b;
    own.solve_in_place(x);
    theirs.solve_in_place(y);
    CHECK(relative_residual(a, x, b) <= kSolveRoundoff);
    CHECK((x - y).lpNorm<Eigen::Infinity>() <= 1e3 * kSolveRoundoff * y.lpNorm<Eigen::Infinity>());
    // Refactored with other values (another cj): the solve reads the new ones.
    const Eigen::SparseMatrix<double> a2 = grid_matrix(mesh.nx, mesh.ny, 40.0, mesh.nz);
    REQUIRE(own.factor(a2));
    x = b;
    own.solve_in_place(x);
    CHECK(relative_residual(a2, x, b) <= kSolveRoundoff);
  }
}

TEST_CASE("a factor whose shared supernodes hold too much keeps CHOLMOD's own solve") {
  // Any split shares its top separator: with no share allowed, CHOLMOD's solve serves.
  const Eigen::SparseMatrix<double> a = grid_matrix(120, 120, 0.5);
  FixedPatternCholmod chol("nesdis", 0.0, 0.0);
  REQUIRE(chol.factor(a));
  REQUIRE(chol.supernodal());
  CHECK(chol.solve_lanes() == 0);
  const Eigen::VectorXd b = right_side(a.rows());
  Eigen::VectorXd x = b;
  chol.solve_in_place(x);
  CHECK(relative_residual(a, x, b) <= kSolveRoundoff);
}

TEST_CASE("the second lane runs both tasks and passes on an exception from either") {
  // The process's lane follows CONDYN_NUM_THREADS and the cores.
  CHECK(SecondLane::shared().lanes() == allowed_lanes());
  setenv("CONDYN_NUM_THREADS", "1", 1);
  CHECK(allowed_lanes() == 1);
  unsetenv("CONDYN_NUM_THREADS");
  for (const int lanes : {1, 2}) {
    SecondLane lane(lanes);
    CHECK(lane.lanes() == lanes);
    std::vector<int> a(1000, 0), b(1000, 0);
    for (int round = 1; round <= 50; ++round) {
      lane.run(
          [&] {
            for (int& v : a) v += round;
          },
          [&] {
            for (int& v : b) v += 2 * round;
          });
    }
    CHECK(a[999] == 50 * 51 / 2);
    CHECK(b[0] == 50 * 51);
    CHECK_THROWS_WITH_AS(lane.run([] {}, [] { throw std::runtime_error("worker"); }), "worker",
                         std::runtime_error);
    CHECK_THROWS_WITH_AS(lane.run([] { throw std::runtime_error("caller"); }, [] {}), "caller",
                         std::runtime_error);
    int after = 0;
    lane.run([&] { ++after; }, [&] { ++after; });
    CHECK(after == 2);
  }
}

TEST_CASE("a process forked after the second lane started runs its task pairs itself") {
  // Python's multiprocessing forks: the worker thread stays in the parent, and a child that
  // waited for it would hang. The child's run must finish; the parent's lane must still work.
  SecondLane lane(2);
  int before = 0;
  lane.run([&] { ++before; }, [&] { ++before; });
  REQUIRE(before == 2);
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    alarm(10);  // a hang ends the child with SIGALRM, which the parent sees
    int count = 0;
    lane.run([&] { ++count; }, [&] { ++count; });
    _exit(count == 2 ? 0 : 1);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  int after = 0;
  lane.run([&] { ++after; }, [&] { ++after; });
  CHECK(after == 2);
}

}  // namespace test_supernodal_solve
