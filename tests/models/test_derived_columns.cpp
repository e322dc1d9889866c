// [[derived]] columns (docs/scenes.md, "Derived columns"): read, resolved against the built
// model (a term on an earlier derived column expanded into its terms), evaluated on a row, and
// every kind of bad input refused with the file, the entry's index and name, and the problem.
#include <doctest/doctest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "models/assembly/build_model.hpp"
#include "models/core/derived_column.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_derived_columns {

namespace {

/// The two-mass chain (u1, u2) held at u1 = 0 by `wall`, with the [[derived]] tables given.
std::string scene(const std::string& derived) {
  return test::kTwoMassChainModel + R"([[constraint]]
name = "wall"
terms = { u1 = 1.0 }
[solve]
t_end = 1.0
output_step = 0.5
)" + derived;
}

}  // namespace

TEST_CASE("derived columns: terms resolved to their quantity and DOF, earlier columns expanded") {
  const Model model = build_model(parse_scene_text(scene(R"([[derived]]
name = "stretch"
terms = { u2 = 1.0, u1 = -1.0 }
[[derived]]
name = "mixed"
terms = { vel_u2 = 2.0, acc_u1 = 3.0, reaction_u1 = -1.0 }
[[derived]]
name = "ratio"
terms = { stretch = 0.5, u2 = 4.0 }
)"),
                                                   "d.toml"));
  REQUIRE(model.derived.size() == 3);
  const auto& stretch = model.derived[0];
  CHECK(stretch.name == "stretch");
  REQUIRE(stretch.terms.size() == 2);  // the terms table's order: u1, then u2
  CHECK(stretch.terms[0].quantity == Quantity::displacement);
  CHECK(stretch.terms[0].index == 0);
  CHECK(stretch.terms[0].coefficient == -1.0);
  CHECK(stretch.terms[1].index == 1);
  CHECK(stretch.terms[1].coefficient == 1.0);
  const auto& mixed = model.derived[1];
  REQUIRE(mixed.terms.size() == 3);
  CHECK(mixed.terms[0].quantity == Quantity::acceleration);
  CHECK(mixed.terms[1].quantity == Quantity::reaction);
  CHECK(mixed.terms[2].quantity == Quantity::velocity);
  // ratio = 0.5 (u2 − u1) + 4 u2: stretch's terms scaled by 0.5, then u2's own.
  const auto& ratio = model.derived[2];
  REQUIRE(ratio.terms.size() == 3);
  CHECK(ratio.terms[0].coefficient == -0.5);
  CHECK(ratio.terms[1].coefficient == 0.5);
  CHECK(ratio.terms[2].coefficient == 4.0);
  CHECK(ratio.terms[2].index == 1);
}

TEST_CASE("derived columns: a row's value is the sum of its terms, and a missing vector is a bug") {
  const DerivedColumn column{"c",
                             {{Quantity::displacement, 1, 2.0},
                              {Quantity::velocity, 0, -1.0},
                              {Quantity::acceleration, 1, 0.5},
                              {Quantity::reaction, 0, 3.0}}};
  const Eigen::Vector2d u(1.0, 10.0), v(7.0, 8.0), a(4.0, 6.0), reaction(-2.0, 5.0);
  // 2·10 − 7 + 0.5·6 + 3·(−2) = 10, every product and sum exact in binary.
  const Eigen::VectorXd none;  // no absolute acceleration: no term reads it
  CHECK(derived_value(column, {u, v, a, none, reaction}) == 10.0);
  CHECK_THROWS_AS((void)derived_value(column, {u, v, none, none, reaction}), std::logic_error);
  CHECK_FALSE(reads_absolute_acceleration({column}));
  // What a run must compute for it: acceleration and reaction beside [output]'s displacement.
  const auto q = with_derived_quantities({Quantity::displacement}, {column});
  CHECK(q == std::vector<Quantity>{Quantity::displacement, Quantity::velocity,
                                   Quantity::acceleration, Quantity::reaction});
  CHECK(with_derived_quantities({Quantity::drift}, {}) == std::vector<Quantity>{Quantity::drift});
}

TEST_CASE("derived columns: bad tables refused as they are read, naming the entry") {
  struct Case {
    std::string derived, where, what;
  };
  const Case cases[] = {
      {"[[derived]]\nterms = { u1 = 1.0 }\n", "bad.toml:12: derived[1]", "name"},
      {"[[derived]]\nname = \"\"\nterms = { u1 = 1.0 }\n", "derived[1].name", "must not be empty"},
      {"[[derived]]\nname = \"a,b\"\nterms = { u1 = 1.0 }\n", "derived[1].name", "holds ','"},
      {"[[derived]]\nname = \"d\"\nterms = { u1 = 1.0 }\n[[derived]]\nname = \"d\"\nterms = { "
       "u2 = 1.0 }\n",
       "bad.toml:16: derived[2].name", "'d' is defined twice (also by derived[1])"},
      {"[[derived]]\nname = \"d\"\n", "derived[1]", "terms"},
      {"[[derived]]\nname = \"d\"\nterms = 1.0\n", "derived[1].terms",
       "derived column 'd': expected a table"},
      {"[[derived]]\nname = \"d\"\nterms = {}\n", "derived[1].terms",
       "derived column 'd': has no terms"},
      {"[[derived]]\nname = \"d\"\nterms = { u1 = \"x\" }\n", "derived[1].terms.u1",
       "derived column 'd': expected a number"},
      {"[[derived]]\nname = \"d\"\nterms = { u1 = inf }\n", "derived[1].terms.u1",
       "derived column 'd': the coefficient inf is not finite"},
      {"[[derived]]\nname = \"d\"\nterms = { u1 = nan }\n", "derived[1].terms.u1",
       "derived column 'd': the coefficient nan is not finite"},
      {"[[derived]]\nname = \"d\"\nterms = { e = 1.0 }\n[[derived]]\nname = \"e\"\nterms = { u1 "
       "= 1.0 }\n",
       "bad.toml:14: derived[1].terms.e",
       "names derived column 'e' of derived[2], which comes after it"},
      {"[[derived]]\nname = \"d\"\nterms = { u1 = 1.0 }\nscale = 2.0\n", "derived[1].scale",
       "unknown key"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.derived);
    const std::string e = test::parse_error(scene(c.derived));
    test::check_refusal(e, c.where);
    CHECK(e.find(c.what) != std::string::npos);
  }
  // A top-level key: before the scene's tables.
  test::check_parse_error("derived = []\n" + scene(""), "bad.toml:1: derived: is empty");
}

TEST_CASE("derived columns: terms the model has no such column for refused when it is built") {
  struct Case {
    std::string derived, where, what;
  };
  const Case cases[] = {
      // A typo: the nearest columns suggested.
      {"[[derived]]\nname = \"d\"\nterms = { u3 = 1.0 }\n", "bad.toml:14: derived[1].terms.u3",
       "derived column 'd': no output column is named 'u3'"},
      {"[[derived]]\nname = \"d\"\nterms = { reaction_u3 = 1.0 }\n", "derived[1].terms.reaction_u3",
       "the nearest: reaction_u1, reaction_u2"},
      // Columns of another kind.
      {"[[derived]]\nname = \"d\"\nterms = { lambda_wall = 1.0 }\n", "derived[1].terms.lambda_wall",
       "'lambda_wall' is a multiplier column: a term names a "
       "displacement, velocity, acceleration or reaction column"},
      {"[[derived]]\nname = \"d\"\nterms = { drift_position = 1.0 }\n",
       "derived[1].terms.drift_position", "is a drift column"},
      {"[[derived]]\nname = \"d\"\nterms = { energy_error = 1.0 }\n",
       "derived[1].terms.energy_error", "is an energy column"},
      // Names that are already a column of the run.
      {"[[derived]]\nname = \"u2\"\nterms = { u1 = 1.0 }\n", "bad.toml:13: derived[1].name",
       "derived column 'u2': the name is already a displacement column of the run"},
      {"[[derived]]\nname = \"vel_u1\"\nterms = { u1 = 1.0 }\n", "derived[1].name",
       "already a velocity column"},
      {"[[derived]]\nname = \"lambda_wall\"\nterms = { u1 = 1.0 }\n", "derived[1].name",
       "already a multiplier column"},
      {"[[derived]]\nname = \"t\"\nterms = { u1 = 1.0 }\n", "derived[1].name",
       "already the time column"},
      {"[[derived]]\nname = \"energy\"\nterms = { u1 = 1.0 }\n", "derived[1].name",
       "already an energy column"},
      {"[[derived]]\nname = \"d\"\nterms = { d = 1.0 }\n", "derived[1].terms.d",
       "derived column 'd': a column cannot be a term of itself"},
      // An earlier column's coefficients scaled past the double range.
      {"[[derived]]\nname = \"d\"\nterms = { u1 = 1e300 }\n[[derived]]\nname = \"e\"\n"
       "terms = { d = 1e300 }\n",
       "bad.toml:17: derived[2].terms.d", "1e+300 times the coefficients of 'd' overflows"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.derived);
    CHECK(test::parse_error(scene(c.derived)).empty());  // the text alone is well formed
    const std::string e = test::build_error(scene(c.derived));
    test::check_refusal(e, c.where);
    CHECK(e.find(c.what) != std::string::npos);
  }
}

TEST_CASE("derived columns: absolute accelerations are terms under [ground_motion] only") {
  // a_g = 0.75 everywhere, r = (1, 2): acc_abs = acc + r a_g, every value exact in binary.
  const std::string ground = R"([ground_motion]
acceleration = 0.75
influence = { u1 = 1.0, u2 = 2.0 }
)";
  const std::string derived = R"([[derived]]
name = "d"
terms = { acc_abs_u2 = 3.0, u1 = 1.0 }
[[derived]]
name = "e"
terms = { d = 2.0, acc_u2 = -6.0 }
)";
  const Model model = build_model(parse_scene_text(
      test::kTwoMassChainModel + ground + "[solve]\nt_end = 1.0\noutput_step = 0.5\n" + derived,
      "d.toml"));
  REQUIRE(model.derived.size() == 2);
  const auto& d = model.derived[0];
  REQUIRE(d.terms.size() == 2);
  CHECK(d.terms[0].quantity == Quantity::absolute_acceleration);
  CHECK(d.terms[0].index == 1);
  CHECK(d.terms[0].coefficient == 3.0);
  // The terms table's order (acc_u2, d), d's terms times 2 in its place.
  const auto& e = model.derived[1];
  REQUIRE(e.terms.size() == 3);
  CHECK(e.terms[0].quantity == Quantity::acceleration);
  CHECK(e.terms[1].quantity == Quantity::absolute_acceleration);
  CHECK(e.terms[1].coefficient == 6.0);
  CHECK(reads_absolute_acceleration(model.derived));
  CHECK(with_derived_quantities({Quantity::displacement}, model.derived) ==
        std::vector<Quantity>{Quantity::displacement, Quantity::absolute_acceleration,
                              Quantity::acceleration});
  // A row: d = 3 (a2 + 2 · 0.75) + u1 = 3 (0.5 + 1.5) + 4 = 10; e = 2 d − 6 a2 = 20 − 3 = 17.
  const Eigen::Vector2d u(4.0, 1.0), v(0.0, 0.0), a(0.25, 0.5), reaction(0.0, 0.0);
  const Eigen::VectorXd values = model.derived_values(0.3, u, v, a, reaction);
  REQUIRE(values.size() == 2);
  CHECK(values[0] == 10.0);
  CHECK(values[1] == 17.0);
  // They are the acc_abs_ columns' own values, a + r a_g(t) (Model::absolute_acceleration).
  CHECK(values[0] == 3.0 * model.absolute_acceleration(0.3, a)[1] + u[0]);
  // A row without accelerations lacks what d reads: a bug of the caller, not a silent value.
  const Eigen::VectorXd none;
  CHECK_THROWS_AS((void)model.derived_values(0.3, u, v, none, reaction), std::logic_error);

  // Without [ground_motion]: no acc_abs_ column, and no r a_g(t) to add.
  const std::string refusal = test::build_error(scene(R"([[derived]]
name = "d"
terms = { acc_abs_u2 = 1.0 }
)"));
  test::check_refusal(refusal, "bad.toml:14: derived[1].terms.acc_abs_u2");
  CHECK(refusal.find(
            "derived column 'd': 'acc_abs_u2' needs [ground_motion]: without a moving ground "
            "the absolute acceleration is the acceleration (name acc_u2)") != std::string::npos);
}

}  // namespace test_derived_columns
