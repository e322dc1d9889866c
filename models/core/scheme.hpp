#pragma once
/// The schemes a scene can be solved with, and their names as scenes, the command line and the
/// reports write them: one table for the parser, the CLI and the solver's dispatch.

#include <optional>
#include <string>
#include <string_view>

namespace condyn {

/// The formulation used to solve the scene (docs/schemes.md).
enum class Scheme {
  automatic,
  elimination,
  index1,
  baumgarte,
  ggl,
  index2,
  index3,
  penalty,
  projection,
  newmark,  ///< the Newmark family (dae/integrators/newmark_stepper.hpp), fixed step
  hht,
  generalized_alpha,
  rattle  ///< RATTLE, symplectic (dae/integrators/rattle_step.hpp), fixed step
};

/// Every runnable scheme, the chapter's reference path first (automatic is not one: it resolves
/// to one of these).
inline constexpr Scheme kSchemes[] = {Scheme::elimination, Scheme::index1,    Scheme::baumgarte,
                                      Scheme::ggl,         Scheme::index2,    Scheme::index3,
                                      Scheme::penalty,     Scheme::projection};

/// The fixed-step schemes ([solve] step), not in kSchemes, the schemes `compare`, `info` and the
/// studies run by default: they are asked for by name. The Newmark family, generalized-α methods at
/// index 3 (docs/schemes.md "The Newmark family"), runs with a fixed step or, without one, with
/// error-controlled steps; RATTLE needs a step.
inline constexpr Scheme kFixedStepSchemes[] = {Scheme::newmark, Scheme::hht,
                                               Scheme::generalized_alpha, Scheme::rattle};
[[nodiscard]] constexpr bool newmark_family(Scheme s) {
  return s == Scheme::newmark || s == Scheme::hht || s == Scheme::generalized_alpha;
}
[[nodiscard]] constexpr bool fixed_step(Scheme s) {
  return newmark_family(s) || s == Scheme::rattle;
}

[[nodiscard]] const char* to_string(Scheme s);
/// The schemes with a multiplier per kept row, which the mixed treatment applies to
/// ([solve] constraints, dae/formulations/constraint_treatment.hpp): the multiplier schemes, the
/// Newmark family, and auto.
[[nodiscard]] constexpr bool mixes(Scheme s) {
  return s == Scheme::automatic || s == Scheme::index1 || s == Scheme::baumgarte ||
         s == Scheme::ggl || s == Scheme::index2 || s == Scheme::index3 || newmark_family(s);
}
/// Why [solve] constraints (--constraints) does not go with the scheme s, which does not mix:
/// "applies to the multiplier schemes (index1, ...), the Newmark family (...) and auto, not to s".
[[nodiscard]] std::string treatment_refusal(Scheme s);
/// The scheme named s ("auto" included), or nothing.
[[nodiscard]] std::optional<Scheme> scheme_from_string(std::string_view s);
/// "auto, elimination, index1, ..." for messages.
[[nodiscard]] std::string scheme_names();

}  // namespace condyn
