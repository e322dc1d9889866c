#pragma once
/// A strict reader of Matrix Market files (scene-format.md, "Matrices and vectors from files"):
/// `%%MatrixMarket matrix coordinate real|integer general|symmetric`, 1-based indices, one entry
/// per line, duplicates summed (as SciPy and Eigen do). A symmetric file holds the lower triangle
/// and is expanded to both. The result is sparse from the first entry on: nothing dense.
///
/// Why not Eigen's unsupported loadMarket (Eigen 3.4, MarketIO.h): it ignores the header, so a
/// symmetric file stays one triangle and a pattern, complex or array file is misread; it prints an
/// out-of-range index or a short entry count to stderr and still returns true; it parses values
/// with sscanf, so "nan" and "inf" pass and a garbled line gives a default value; and it reports
/// no line for anything. Scenes need each of those refused with the file's line.

#include <Eigen/Sparse>
#include <optional>
#include <stdexcept>
#include <string>

namespace condyn {

/// A malformed Matrix Market file: `line` is the 1-based line of the file (0 when the whole file
/// is at fault, e.g. it cannot be opened); what() says what is wrong.
class MatrixMarketError : public std::runtime_error {
 public:
  MatrixMarketError(int line, const std::string& what) : std::runtime_error(what), line_(line) {}
  [[nodiscard]] int line() const { return line_; }

 private:
  int line_;
};

struct MarketMatrix {
  Eigen::SparseMatrix<double> matrix;  ///< rows x cols, compressed, symmetric storage expanded
  bool symmetric = false;              ///< the header said `symmetric`
};

/// What the caller knows of a file before reading it, checked at its size line, before anything
/// is allocated: a size line that disagrees with the model (a typo of 3·10⁸ for 3) was
/// refused only after its index arrays were filled, gigabytes and seconds later.
struct MarketExpectation {
  /// Constraint blocks: a size line declaring more rows than entries is refused at once,
  /// since some row would be empty.
  bool rows_need_entries = false;
  long long rows = 0, cols = 0;  ///< the size the file must declare; 0: any
  std::string because;           ///< why, for the message ("M.mtx is 3 x 3")
  /// What to look at, closing the message: the size line, unless the size comes from another
  /// file of the scene, which may be the wrong one.
  std::string advice = "is the size line right?";
  /// A model matrix (mass, damping, stiffness): its rows are DOFs, and a size line declaring
  /// more than the machine could integrate (models/core/memory_estimate.hpp's lower bound, beside
  /// the matrix itself) is refused before the DOFs are built.
  bool rows_are_dofs = false;
};

/// The checks of a matrix's declared size made before anything is held, shared by every route a
/// matrix comes in (a file's size line; an array handed over by Python, python/scene_from_python):
/// a size outside 1 to 2^31 - 1 (KLU's and Eigen's 32-bit indices), as "the size R x C is not
/// between 1 and 2^31 - 1"; nothing when it is inside.
[[nodiscard]] std::optional<std::string> size_range_refusal(long long rows, long long cols);

/// More memory than is available for holding a rows x cols matrix of `entries` stored entries
/// (both triangles of a symmetric one) and, when `rows_are_dofs` (M, C or K), for integrating a
/// model of `rows` DOFs (models/core/memory_estimate.hpp's lower bound): "holding it [and
/// integrating a model of N DOFs] needs [at least] X, more than the Y this machine has available
/// (MemAvailable in /proc/meminfo)"; nothing when it may fit or /proc/meminfo cannot be read.
[[nodiscard]] std::optional<std::string> holding_refusal(long long rows, long long cols,
                                                         double entries, bool rows_are_dofs);

/// Reads `path`. Throws MatrixMarketError for anything but a well-formed coordinate real (or
/// integer) general or symmetric file with finite values and indices inside the declared size,
/// and for a size line `expect` refuses.
[[nodiscard]] MarketMatrix read_matrix_market(const std::string& path,
                                              const MarketExpectation& expect = {});
/// The same, from the file's text (tests).
[[nodiscard]] MarketMatrix parse_matrix_market(const std::string& text,
                                               const MarketExpectation& expect = {});

}  // namespace condyn
