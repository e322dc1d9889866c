#pragma once
/// Where a value of the user's input came from, and the error that names it: a scene's key and
/// line ("constraint[3].terms.ux9", line 41), or a command line's flag (line 0). The parser, the
/// model builder and the solver's refusals (a scheme that does not apply, a run too large for the
/// memory) report bad input through these, in one house style.

#include <stdexcept>
#include <string>

namespace condyn {

/// Where a value came from, for error messages: "constraint[3].terms.ux9" and line 41.
struct SourcePoint {
  std::string path;
  int line = 0;  ///< 1-based; 0 when unknown
};

/// A problem with the user's input. what() reads "FILE:LINE: PATH: problem" (LINE omitted when
/// unknown). Indices in paths are 1-based, as in the scene: load[2] is the second [[load]].
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Formats an input error in the one house style.
[[nodiscard]] std::string scene_message(const std::string& file, const SourcePoint& where,
                                        const std::string& problem);

}  // namespace condyn
