#pragma once
/// The chapter's printed matrices beside the ones condyn assembles, with every differing entry
/// flagged, and the errata that follow from them (and from the chapter's checkable claims).

#include <Eigen/Dense>
#include <ostream>
#include <string>
#include <vector>

#include "validation/references/chapter_printed.hpp"

namespace condyn {

struct MatrixComparison {
  PrintedMatrix printed;
  Eigen::MatrixXd computed;
  std::vector<std::pair<int, int>> differing;  ///< 0-based (row, col)
};

struct Erratum {
  std::string where;        ///< "5.7" or "§5.6.1 text"
  std::string description;  ///< what is printed, what is right, how the code knows
};

struct ChapterCaseReport {
  std::string scene, section;
  std::vector<MatrixComparison> comparisons;
  std::vector<std::string> notes;  ///< checks that are not matrices (eq. 5.14, rank claims)
};

struct ChapterReport {
  std::vector<ChapterCaseReport> cases;
  std::vector<Erratum> errata;
};

/// Builds every case from its embedded scene and compares. Printed entries equal to the computed
/// ones within kPrintedTolerance (relative) count as agreeing.
[[nodiscard]] ChapterReport chapter_report();

void print_case_matrices(std::ostream& out, const ChapterCaseReport& report);
void print_errata(std::ostream& out, const std::vector<Erratum>& errata);

}  // namespace condyn
