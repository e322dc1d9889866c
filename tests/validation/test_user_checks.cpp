// [[check]] tables (scene-format.md, "Checks for a user's own validation suite"): how they are read
// and refused, and how they are evaluated on a run whose exact solution is known.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/scene_errors.hpp"
#include "validation/studies/user_checks.hpp"

using namespace condyn;

namespace test_user_checks {

namespace {

/// A unit oscillator (m = k = 1) released from u = 1: u(t) = cos t exactly, v(t) = −sin t.
std::string oscillator(const std::string& checks) {
  return R"(name = "oscillator"
[model]
type = "matrix"
dofs = ["x"]
mass = [[1.0]]
stiffness = [[1.0]]
[initial]
displacement = { x = 1.0 }
[solve]
t_end = 2.0
output_step = 0.1
scheme = "index1"
rtol = 1e-10
atol = 1e-12
)" + checks;
}

/// The reader's refusal of `text`, or "(accepted)".
std::string refusal(const std::string& text) {
  const std::string message = test::parse_error(text, "s.toml");
  return message.empty() ? "(accepted)" : message;
}

}  // namespace

TEST_CASE("checks: each bad [[check]] is refused naming its key and line") {
  struct Case {
    const char* checks;
    const char* expected;
  };
  const Case cases[] = {
      {"[[check]]\nquantity = \"x\"\nmax_abs = 1.0\nat = 1.0\nvalue = 0.5\ntolerance = 1e-3\n",
       "s.toml:15: check[1]: give exactly one of"},
      {"[[check]]\nquantity = \"x\"\n", "check[1]: give exactly one of"},
      {"[[check]]\nquantity = \"x\"\nat = 0.25\nvalue = 0.5\ntolerance = 1e-3\n",
       "check[1].at: is not an output time (multiples of output_step 0.1 and t_end; the nearest "
       "are 0.2 and 0.3)"},
      {"[[check]]\nquantity = \"x\"\nat = 3.0\nvalue = 0.5\ntolerance = 1e-3\n",
       "check[1].at: is outside the run, [0, 2]"},
      {"[[check]]\nquantity = \"x\"\nat = 1.0\nvalue = 0.5\n", "check[1].tolerance"},
      {"[[check]]\nquantity = \"x\"\nmax_abs = -1.0\n", "check[1].max_abs: must be >= 0"},
      {"[[check]]\nquantity = \"x\"\nmax_abs = 1.0\ntolerance = 1.0\n",
       "check[1].tolerance: does not go with max_abs"},
      {"[[check]]\nquantity = \"x\"\nmax_abs = nan\n", "check[1].max_abs"},
      {"[[check]]\nquantity = \"x\"\nmax_abs = 1.0\nbound = 2.0\n", "check[1].bound: unknown key"},
      {"[[check]]\nquantity = \"\"\nmax_abs = 1.0\n", "check[1].quantity: must not be empty"},
      {"[[check]]\nquantity = \"x\"\nreference = { file = \"missing.csv\" }\ntolerance = 1.0\n",
       "check[1].reference.file: missing.csv"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.checks);
    const std::string message = refusal(oscillator(c.checks));
    CAPTURE(message);
    CHECK(message.find(c.expected) != std::string::npos);
  }
}

TEST_CASE("checks: a bound of -0.0 is 0") {
  // Not refused (it is no negative number) and not printed 'bound -0'.
  const SceneSpec spec =
      parse_scene_text(oscillator("[[check]]\nquantity = \"x\"\nmax_abs = -0.0\n"), "s.toml");
  REQUIRE(spec.checks.size() == 1);
  CHECK(spec.checks[0].bound == 0.0);
  CHECK(!std::signbit(spec.checks[0].bound));
}

TEST_CASE("checks: an unknown column is refused with the nearest names") {
  SceneSpec spec =
      parse_scene_text(oscillator("[[check]]\nquantity = \"vel_y\"\nmax_abs = 1.0\n"), "s.toml");
  try {
    (void)run_scene_checks(spec);
    FAIL("accepted an unknown column");
  } catch (const SceneError& e) {
    const std::string m = e.what();
    CAPTURE(m);
    CHECK(m.find("s.toml:15: check[1].quantity: no output column is named 'vel_y'") == 0);
    CHECK(m.find("the nearest: vel_x") != std::string::npos);
  }
  spec.checks.clear();
  CHECK_THROWS_WITH_AS((void)run_scene_checks(spec), doctest::Contains("has no [[check]] table"),
                       SceneError);
  // The multiplier of a constraint that redundant = "drop" removed: named as dropped.
  const std::string pair = R"(
[[constraint]]
name = "hold"
terms = { x = 1.0 }
[[constraint]]
name = "again"
terms = { x = 2.0 }
[[check]]
quantity = "lambda_again"
max_abs = 1.0
)";
  std::string text = oscillator(pair);
  text.replace(text.find("displacement = { x = 1.0 }"), 26, "displacement = { x = 0.0 }");
  text.replace(text.find("[solve]\n"), 8, "[solve]\nredundant = \"drop\"\n");
  SceneSpec dropped = parse_scene_text(text, "s.toml");
  CHECK_THROWS_WITH_AS((void)run_scene_checks(dropped),
                       doctest::Contains("check[1].quantity: constraint 'again' was dropped as "
                                         "redundant ([solve] redundant = \"drop\")"),
                       SceneError);
}

TEST_CASE("checks: evaluated against the oscillator's closed form, u = cos t") {
  // The reference file samples cos t at 0.05, between the output times (0.1 apart): the run's
  // values are interpolated linearly there, which costs at most h²/8 max|u''| = 0.1²/8 = 1.25e-3
  // (the integration error, rtol 1e-10, is far below). So a tolerance of 2e-3 holds and 1e-4 fails,
  // which shows the interpolation is what is compared.
  const auto dir = std::filesystem::temp_directory_path() / "condyn_user_checks";
  std::filesystem::create_directories(dir);
  {
    std::ofstream ref(dir / "ref.csv");
    ref << "t,x\n";
    for (int k = 0; k <= 40; ++k) ref << 0.05 * k << "," << std::cos(0.05 * k) << "\n";
  }
  const std::string checks = R"(
[[check]]
quantity = "x"
at = 1.0
value = 0.5403023058681398
tolerance = 1e-7
[[check]]
quantity = "vel_x"
max_abs = 1.0000001
[[check]]
quantity = "x"
reference = { file = "ref.csv" }
tolerance = 2e-3
[[check]]
quantity = "x"
reference = { file = "ref.csv" }
tolerance = 1e-4
[[check]]
quantity = "x"
at = 1.0
value = 0.5
tolerance = 1e-3
[[check]]
quantity = "drift_position"
max_abs = 0.0
)";
  std::ofstream(dir / "s.toml") << oscillator(checks);
  const SceneCheckResult r = run_scene_checks((dir / "s.toml").string());
  REQUIRE(r.failure.empty());
  REQUIRE(r.outcomes.size() == 6);
  // cos(1) = 0.5403023058681398; the run is within 1e-7 of it.
  CHECK(r.outcomes[0].passed);
  CHECK(r.outcomes[0].computed < 1e-7);
  // max |sin t| over [0, 2] is 1 (at t = π/2, between output times: max over rows below 1).
  CHECK(r.outcomes[1].passed);
  CHECK(r.outcomes[1].computed == doctest::Approx(std::sin(1.6)).epsilon(1e-8));
  // The interpolation error of linear interpolation, at most 1.25e-3, and at least the value at
  // t = 0.05 between rows 0 and 0.1: |cos 0.05 − (1 + cos 0.1)/2| = 1.25e-3 cos(...) ≈ 1.2e-3.
  CHECK(r.outcomes[2].passed);
  CHECK(r.outcomes[2].computed > 1e-3);
  CHECK(r.outcomes[2].computed <= 1.25e-3);
  CHECK_FALSE(r.outcomes[3].passed);
  // |cos 1 − 0.5| = 0.0403 > 1e-3.
  CHECK_FALSE(r.outcomes[4].passed);
  CHECK(r.outcomes[4].computed == doctest::Approx(0.0403023058681398).epsilon(1e-6));
  CHECK(r.outcomes[4].text.find("x at t = 1: 0.54030230") == 0);
  CHECK(r.outcomes[4].text.find(", expected 0.5 +- 0.001 (off by 0.04030230") != std::string::npos);
  // No constraints: no drift at all.
  CHECK(r.outcomes[5].passed);
  CHECK_FALSE(r.passed());
  std::filesystem::remove_all(dir);
}

TEST_CASE("checks: a time 1e-10 before t_end is its own row, not t_end's") {
  // output_step 1.9999999999 on t_end 2: rows 0, 1.9999999999 and 2. The row 1e-10 before t_end
  // was dropped (a tolerance of 1e-9 output steps) and a check there read the row of t = 2.
  std::string text = oscillator(
      "[[check]]\nquantity = \"x\"\nat = 1.9999999999\nvalue = 0.0\ntolerance = 1.0\n"
      "[[check]]\nquantity = \"x\"\nat = 2.0\nvalue = 0.0\ntolerance = 1.0\n");
  text.replace(text.find("output_step = 0.1"), 17, "output_step = 1.9999999999");
  const SceneCheckResult r = run_scene_checks(parse_scene_text(text, "s.toml"));
  REQUIRE(r.outcomes.size() == 2);
  // The figure is |x − 0| = |cos t| (cos < 0 there): the rows differ by sin(2) · 1e-10 = 9.1e-11,
  // far above the run's error near t_end at rtol 1e-10 (the two rows share it).
  CHECK(r.outcomes[0].computed == doctest::Approx(-std::cos(1.9999999999)).epsilon(1e-8));
  CHECK(r.outcomes[1].computed - r.outcomes[0].computed ==
        doctest::Approx(std::sin(2.0) * 1e-10).epsilon(0.05));
}

}  // namespace test_user_checks
