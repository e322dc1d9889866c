// "Did you mean" (models/core/nearest_names.hpp): the measure every refusal that suggests names
// shares, and what it suggests (issue 42: check listed the first five DOFs, not the nearest).
#include "models/core/nearest_names.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "validation/studies/user_checks.hpp"

namespace test_nearest_names {

using condyn::name_distance;
using condyn::nearest_names;

namespace {

using Names = std::vector<std::string>;

/// A planar frame's DOFs, in the model's order: ux1, uy1, ..., ux12, uy12.
Names frame_dofs() {
  Names out;
  for (int node = 1; node <= 12; ++node) {
    out.push_back("ux" + std::to_string(node));
    out.push_back("uy" + std::to_string(node));
  }
  return out;
}

/// A scene of 24 unit oscillators named as frame_dofs(), to t = 1.
std::string frame_scene() {
  const Names dofs = frame_dofs();
  std::string names, diagonal;
  for (std::size_t k = 0; k < dofs.size(); ++k) names += (k ? ", \"" : "\"") + dofs[k] + "\"";
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    diagonal += i ? ", [" : "[";
    for (std::size_t j = 0; j < dofs.size(); ++j)
      diagonal += (j ? ", " : "") + std::string(i == j ? "1.0" : "0.0");
    diagonal += "]";
  }
  return "name = \"frame\"\n[model]\ntype = \"matrix\"\ndofs = [" + names + "]\nmass = [" +
         diagonal + "]\nstiffness = [" + diagonal + "]\n[solve]\nt_end = 1.0\noutput_step = 0.5\n";
}

}  // namespace

TEST_CASE("name_distance: edits and swaps of neighbours count 1 each, case does not count") {
  CHECK(name_distance("ux3", "ux3") == 0);
  CHECK(name_distance("UX3", "ux3") == 0);
  CHECK(name_distance("uz3", "ux3") == 1);     // a substitution
  CHECK(name_distance("uy_12", "uy12") == 1);  // a deletion
  CHECK(name_distance("uy12", "uy_12") == 1);  // an insertion
  CHECK(name_distance("tpi", "tip") == 1);     // neighbours swapped (plain Levenshtein: 2)
  CHECK(name_distance("", "abc") == 3);
  CHECK(name_distance("kitten", "sitting") == 3);  // the textbook example
}

TEST_CASE("nearest_names: the names a typo meant, nearest first, or none") {
  const Names dofs = frame_dofs();
  // Plain edit distance ranked every name and took the first five: uy12 then uy1, ux12 ... at
  // distance 2, unrelated. Only the near one now.
  CHECK(nearest_names("uy_12", dofs) == Names{"uy12"});
  CHECK(nearest_names("uz3", dofs) == Names{"ux3", "uy3"});
  CHECK(nearest_names("UX7", dofs) == Names{"ux7"});
  // Nothing near: no list at all, rather than the model's first names.
  CHECK(nearest_names("rotation", dofs).empty());
  CHECK(nearest_names("q", Names{"a", "b", "c"}).empty());
  // A name inside another, or the other way round (three characters and more).
  CHECK(nearest_names("drift_pos", Names{"drift_position", "drift_velocity", "energy"}) ==
        Names{"drift_position"});
  CHECK(nearest_names("displacement_uy3", dofs) == Names{"uy3"});
  // The nearest alone (ux7, not ux1 or uy7 one edit further), at most `most` of them, in the
  // candidates' order.
  CHECK(nearest_names("ux", dofs, 3) == Names{"ux1", "ux2", "ux3"});
  CHECK(nearest_names("ux_7", dofs) == Names{"ux7"});
  CHECK(condyn::joined_names(Names{"a", "b"}) == "a, b");
}

TEST_CASE("a check's unknown column: only the nearest names are suggested") {
  const std::string scene = frame_scene();
  for (const auto& [name, said] :
       {std::pair<std::string, std::string>{"uy_12", "; the nearest: uy12"},
        {"vel_uy_12", "; the nearest: vel_uy12"},
        {"rotation", "; no column's name is near it"}}) {
    const std::string quantity = name;  // CAPTURE's lambda cannot name a binding (clang 14)
    CAPTURE(quantity);
    const condyn::SceneSpec spec = condyn::parse_scene_text(
        scene + "[[check]]\nquantity = \"" + quantity + "\"\nmax_abs = 1.0\n", "f.toml");
    try {
      (void)condyn::run_scene_checks(spec);
      FAIL("accepted an unknown column");
    } catch (const condyn::SceneError& e) {
      const std::string m = e.what();
      CAPTURE(m);
      // The message ends with the suggestion: nothing after it (the old one went on to four more
      // names at distance 2: uy1, uy2, ux12, ...).
      CHECK(m.ends_with(said));
    }
  }
}

TEST_CASE("a scene's unknown DOF and unknown key: the nearest name, when one is near") {
  // A DOF: the nearest of a model too large to list them all (over 12 DOFs).
  const auto dof_error = [](const std::string& dof) {
    try {
      (void)condyn::build_model(condyn::parse_scene_text(
          frame_scene() + "[[constraint]]\nterms = { " + dof + " = 1.0 }\n", "f.toml"));
      return std::string();
    } catch (const condyn::SceneError& e) {
      return std::string(e.what());
    }
  };
  CHECK(dof_error("uy_12").find("no such DOF 'uy_12' (the nearest: uy12)") != std::string::npos);
  // None near, and too many to list: the name alone (no list of unrelated DOFs).
  CHECK(dof_error("rotation").ends_with("no such DOF 'rotation'"));
  const std::string base = condyn::test::kTwoMassesScene;
  const auto error = [](const std::string& text) {
    try {
      (void)condyn::parse_scene_text(text, "s.toml");
      return std::string();
    } catch (const condyn::SceneError& e) {
      return std::string(e.what());
    }
  };
  CHECK(error(base + "[output]\nquantites = [\"displacement\"]\n")
            .find("unknown key (did you mean quantities? expected one of: ") != std::string::npos);
  CHECK(error(base + "[output]\nzzz = 1\n").find("unknown key (expected one of: ") !=
        std::string::npos);
}

}  // namespace test_nearest_names
