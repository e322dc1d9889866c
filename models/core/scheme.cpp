#include "models/core/scheme.hpp"

namespace condyn {

const char* to_string(Scheme s) {
  switch (s) {
    case Scheme::automatic:
      return "auto";
    case Scheme::elimination:
      return "elimination";
    case Scheme::index1:
      return "index1";
    case Scheme::baumgarte:
      return "baumgarte";
    case Scheme::ggl:
      return "ggl";
    case Scheme::index2:
      return "index2";
    case Scheme::index3:
      return "index3";
    case Scheme::penalty:
      return "penalty";
    case Scheme::projection:
      return "projection";
    case Scheme::newmark:
      return "newmark";
    case Scheme::hht:
      return "hht";
    case Scheme::generalized_alpha:
      return "generalized_alpha";
    case Scheme::rattle:
      return "rattle";
  }
  return "?";
}

std::optional<Scheme> scheme_from_string(std::string_view s) {
  if (s == to_string(Scheme::automatic)) return Scheme::automatic;
  for (Scheme scheme : kSchemes) {
    if (s == to_string(scheme)) return scheme;
  }
  for (Scheme scheme : kFixedStepSchemes) {
    if (s == to_string(scheme)) return scheme;
  }
  return std::nullopt;
}

std::string treatment_refusal(Scheme s) {
  return std::string(
             "applies to the multiplier schemes (index1, baumgarte, ggl, index2, index3), "
             "the Newmark family (newmark, hht, generalized_alpha) and auto, not to ") +
         to_string(s);
}

std::string scheme_names() {
  std::string names = to_string(Scheme::automatic);
  for (Scheme scheme : kSchemes) names += std::string(", ") + to_string(scheme);
  for (Scheme scheme : kFixedStepSchemes) names += std::string(", ") + to_string(scheme);
  return names;
}

}  // namespace condyn
