#pragma once
/// What `condyn check` prints and writes: one line per check with its computed figure and its
/// bound, a summary, and the JUnit XML report CI systems read (one testsuite per scene, one
/// testcase per check; a failed check is a <failure>, a run that failed or a scene that could not
/// be read an <error>).

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "validation/studies/user_checks.hpp"

namespace condyn {

/// One scene given to `condyn check`: its result, or why it could not be checked.
struct CheckedScene {
  std::string scene;
  std::optional<SceneCheckResult> result;
  std::string error;     ///< bad input or a set-up failure, when there is no result
  int exit_code = 0;     ///< 0 all hold, 1 a check or the run failed, 2 bad input
  double seconds = 0.0;  ///< wall time of the whole scene (parse, build, run)
};

/// The exit code of one scene's result (0 or 1).
[[nodiscard]] int exit_code_of(const SceneCheckResult& result);

void print_checked_scene(std::ostream& out, const CheckedScene& scene);
/// "checks: 7 passed, 1 failed, 1 scene not checked (bad input)".
void print_check_summary(std::ostream& out, const std::vector<CheckedScene>& scenes);

/// The JUnit XML report (the schema Jenkins, GitLab and GitHub Actions read).
[[nodiscard]] std::string junit_xml(const std::vector<CheckedScene>& scenes);

}  // namespace condyn
