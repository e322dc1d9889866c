// Issue 47 item 8: support motion. A displacement record (models/core/kinematic_record.hpp) as a
// constraint's right-hand side: the quintic Hermite interpolant of a record triple and its
// derivatives, the exact double integration of an acceleration record and its linear baseline,
// and the scene's refusals (each naming the scene's key, and the CSV file and line where one is
// at fault).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "models/assembly/build_model.hpp"
#include "models/core/kinematic_record.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_support_motion {

using condyn::test::Sandbox;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// A table of `values` at `times` (as the CSV reader returns it).
TimeTable table_of(const std::vector<double>& times, const std::vector<double>& values) {
  TimeTable t;
  t.file = "t.csv";
  t.column = "x";
  t.times = times;
  t.values = values;
  for (std::size_t k = 0; k < times.size(); ++k) t.lines.push_back(static_cast<int>(k) + 2);
  return t;
}

/// p(t) = 1 + 2t − t² + 0.5t³ − 0.25t⁴ + 0.125t⁵ and its first two derivatives.
double quintic(int order, double t) {
  const double c[6] = {1.0, 2.0, -1.0, 0.5, -0.25, 0.125};
  double sum = 0.0;
  for (int j = order; j < 6; ++j) {
    double f = 1.0;
    for (int i = 0; i < order; ++i) f *= j - i;
    sum += f * c[j] * std::pow(t, j - order);
  }
  return sum;
}

std::string csv(const std::vector<double>& t, const std::vector<std::vector<double>>& cols,
                const std::string& header) {
  std::ostringstream s;
  s.precision(17);
  s << header << "\n";
  for (std::size_t k = 0; k < t.size(); ++k) {
    s << t[k];
    for (const auto& c : cols) s << "," << c[k];
    s << "\n";
  }
  return s.str();
}

/// A matrix model of one mass between a support DOF `s` and a fixed one, `s` prescribed by
/// `value` (a TOML inline table or list).
std::string scene_with(const std::string& value, double t_end = 1.0) {
  std::ostringstream s;
  s << R"([model]
type = "matrix"
dofs = ["s", "u"]
mass = [[0.0, 0.0], [0.0, 1.0]]
stiffness = [[4.0, -4.0], [-4.0, 8.0]]
[[constraint]]
name = "left"
terms = { s = 1.0 }
value = )"
    << value << "\n[solve]\nt_end = " << t_end << "\noutput_step = 0.1\n";
  return s.str();
}

/// The scene error of `text` built from the sandbox's folder.
std::string error_in(const Sandbox& box, const std::string& text) {
  return condyn::test::file_build_error(box.write("bad.toml", text).string());
}

bool has(const std::string& s, const std::string& needle) {
  return s.find(needle) != std::string::npos;
}

}  // namespace

TEST_CASE("support motion: a record triple of a quintic is reproduced with its derivatives") {
  // The quintic Hermite interpolant of a quintic's samples is the quintic itself: every piece,
  // whatever its length (uneven samples), to roundoff of the values (of order 10 on [0, 2]).
  const std::vector<double> t = {0.0, 0.3, 0.45, 1.1, 2.0};
  std::vector<double> d, v, a;
  for (double x : t) {
    d.push_back(quintic(0, x));
    v.push_back(quintic(1, x));
    a.push_back(quintic(2, x));
  }
  const KinematicRecord r =
      record_from_triple(table_of(t, d), table_of(t, v), table_of(t, a), "t.csv:d,v,a");
  constexpr double kRoundoff = 256 * kEps * 10.0;  // a few dozen operations on values of 10
  for (double x = 0.0; x <= 2.0; x += 0.0625) {
    CAPTURE(x);
    for (int order = 0; order <= 2; ++order) {
      CHECK(std::abs(r.derivative(order, x) - quintic(order, x)) <= kRoundoff);
    }
  }
  // Outside its samples it holds its end displacements, at rest.
  CHECK(r.derivative(0, -1.0) == d.front());
  CHECK(r.derivative(0, 3.0) == d.back());
  CHECK(r.derivative(1, 3.0) == 0.0);
  CHECK(r.derivative(2, -1.0) == 0.0);
  // The bounds hold the interpolant's peaks (sampled above).
  for (double x = 0.0; x <= 2.0; x += 0.0625) {
    for (int order = 0; order <= 2; ++order) {
      CHECK(std::abs(r.derivative(order, x)) <= r.bound[static_cast<std::size_t>(order)]);
    }
  }
}

TEST_CASE("support motion: the interpolant is twice continuously differentiable at samples") {
  // Samples that no single polynomial fits (a kinked triple): left and right limits agree in
  // value, slope and curvature at every inner sample, to roundoff of the values.
  const std::vector<double> t = {0.0, 1.0, 2.5, 3.0};
  const std::vector<double> d = {0.0, 1.0, -0.5, 0.2}, v = {0.0, 3.0, 1.0, -2.0},
                            a = {1.0, -4.0, 6.0, 0.0};
  const KinematicRecord r =
      record_from_triple(table_of(t, d), table_of(t, v), table_of(t, a), "kinked");
  for (std::size_t k = 1; k + 1 < t.size(); ++k) {
    const double left = std::nextafter(t[k], 0.0);
    CHECK(r.derivative(0, t[k]) == doctest::Approx(d[k]).epsilon(1e-13));
    CHECK(r.derivative(1, t[k]) == doctest::Approx(v[k]).epsilon(1e-13));
    CHECK(r.derivative(2, t[k]) == doctest::Approx(a[k]).epsilon(1e-13));
    CHECK(r.derivative(0, left) == doctest::Approx(d[k]).epsilon(1e-12));
    CHECK(r.derivative(1, left) == doctest::Approx(v[k]).epsilon(1e-12));
    CHECK(r.derivative(2, left) == doctest::Approx(a[k]).epsilon(1e-12));
  }
}

TEST_CASE("support motion: a triple whose sample times differ names the part and its line") {
  const TimeTable d = table_of({0.0, 1.0, 2.0}, {0.0, 1.0, 0.0});
  const TimeTable v = table_of({0.0, 1.5, 2.0}, {0.0, 0.0, 0.0});
  const TimeTable a = table_of({0.0, 1.0}, {0.0, 0.0});
  try {
    (void)record_from_triple(d, v, d, "x");
    FAIL("no mismatch reported");
  } catch (const RecordMismatch& e) {
    CHECK(e.part() == "velocity");
    CHECK(e.line() == 3);  // the second sample's line
    CHECK(has(e.what(), "sample 2 is at t = 1.5"));
  }
  try {
    (void)record_from_triple(d, d, a, "x");
    FAIL("no mismatch reported");
  } catch (const RecordMismatch& e) {
    CHECK(e.part() == "acceleration");
    CHECK(has(e.what(), "has 2 samples, the displacement's (t.csv) 3"));
  }
}

TEST_CASE("support motion: an acceleration record is integrated twice exactly") {
  // a(t) piecewise linear through (0, 0), (1, 2), (3, 2): v = t², d = t³/3 on [0, 1]; then
  // v = 1 + 2(t − 1), d = 1/3 + (t − 1) + (t − 1)² on [1, 3].
  const TimeTable acc = table_of({0.0, 1.0, 3.0}, {0.0, 2.0, 2.0});
  const KinematicRecord r = record_from_acceleration(acc, Baseline::none, "a");
  constexpr double kRoundoff = 64 * kEps * 10.0;  // values of order 10
  for (double t = 0.0; t <= 3.0; t += 0.125) {
    CAPTURE(t);
    const bool first = t <= 1.0;
    const double s = t - 1.0;
    const double d = first ? t * t * t / 3.0 : 1.0 / 3.0 + s + s * s;
    const double v = first ? t * t : 1.0 + 2.0 * s;
    const double a = first ? 2.0 * t : 2.0;
    CHECK(std::abs(r.derivative(0, t) - d) <= kRoundoff);
    CHECK(std::abs(r.derivative(1, t) - v) <= kRoundoff);
    CHECK(std::abs(r.derivative(2, t) - a) <= kRoundoff);
  }
}

TEST_CASE("support motion: the linear baseline removes a linear drift of the acceleration") {
  // A record that ends at rest plus a linear error c0 + c1 t (a baseline offset and a tilt, as an
  // accelerometer's): corrected, it is the record alone (the correction is linear and removes any
  // linear part exactly), and it ends at rest; uncorrected, the error drifts the displacement.
  std::vector<double> t, pulse, drifted;
  const double T = 2.0, w = 2.0 * M_PI / T;
  for (int k = 0; k <= 200; ++k) {
    t.push_back(T * k / 200.0);
    // the acceleration of (1 − cos wt)²: at rest at both ends, to second order
    const double s = std::sin(w * t.back()), c = std::cos(w * t.back());
    pulse.push_back(2.0 * w * w * (s * s + (1.0 - c) * c));
    drifted.push_back(pulse.back() + 0.3 + 0.2 * t.back());
  }
  const KinematicRecord clean = record_from_acceleration(table_of(t, pulse), Baseline::linear, "");
  const KinematicRecord fixed =
      record_from_acceleration(table_of(t, drifted), Baseline::linear, "");
  const KinematicRecord raw = record_from_acceleration(table_of(t, drifted), Baseline::none, "");
  // Roundoff of sums over 200 pieces of terms of size max|a| T² ≈ 40.
  const double kRoundoff = 200 * 64 * kEps * 40.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    CHECK(std::abs(fixed.displacement[k] - clean.displacement[k]) <= kRoundoff);
    CHECK(std::abs(fixed.velocity[k] - clean.velocity[k]) <= kRoundoff);
  }
  CHECK(std::abs(fixed.displacement.back()) <= kRoundoff);
  CHECK(std::abs(fixed.velocity.back()) <= kRoundoff);
  // Uncorrected: d(T) gains 0.3 T²/2 + 0.2 T³/6 = 0.8667 over the pulse's own end value.
  CHECK(raw.displacement.back() - clean.displacement.back() ==
        doctest::Approx(0.3 * T * T / 2 + 0.2 * T * T * T / 6).epsilon(1e-9));
}

TEST_CASE("support motion: a displacement record as a constraint's right-hand side") {
  Sandbox box;
  std::vector<double> t, d, v, a;
  for (int k = 0; k <= 20; ++k) {
    t.push_back(0.1 * k);
    d.push_back(0.01 * std::pow(std::sin(0.5 * M_PI * t.back()), 2));
    v.push_back(0.01 * 0.5 * M_PI * std::sin(M_PI * t.back()));
    a.push_back(0.01 * 0.5 * M_PI * M_PI * std::cos(M_PI * t.back()));
  }
  box.write("left.csv", csv(t, {d, v, a}, "t,d,v,a"));
  const std::string value =
      R"({ type = "displacement_record", file = "left.csv", displacement = "d", velocity = "v", acceleration = "a", scale = 2.0 })";
  const Model model =
      build_model(parse_scene_file(box.write("s.toml", scene_with(value)).string()));
  const TimeFunction& g = model.constraints.at(0).position_value;
  REQUIRE(g.has_record());
  CHECK(g.describe() == "record(left.csv:d, left.csv:v, left.csv:a, 21 samples)*2");
  // At a sample the function and its derivatives are the record's, times the scale.
  CHECK(g.derivative(0, 0.5) == doctest::Approx(2.0 * d[5]).epsilon(1e-14));
  CHECK(g.derivative(1, 0.5) == doctest::Approx(2.0 * v[5]).epsilon(1e-14));
  CHECK(g.derivative(2, 0.5) == doctest::Approx(2.0 * a[5]).epsilon(1e-14));
  CHECK_FALSE(g.is_constant());

  // Separate files per part, each with its own column and scale (mixed units: cm and m).
  std::vector<double> d_cm;
  for (double x : d) d_cm.push_back(100.0 * x);
  box.write("d.csv", csv(t, {d_cm}, "t,d_cm"));
  box.write("va.csv", csv(t, {v, a}, "t,v,a"));
  const std::string split =
      R"({ type = "displacement_record", displacement = { file = "d.csv", column = "d_cm", scale = 0.01 }, velocity = { file = "va.csv", column = "v" }, acceleration = { file = "va.csv", column = "a" } })";
  const Model split_model =
      build_model(parse_scene_file(box.write("s2.toml", scene_with(split)).string()));
  const TimeFunction& g2 = split_model.constraints.at(0).position_value;
  for (double x = 0.0; x <= 2.0; x += 0.05) {
    CHECK(g2.derivative(0, x) == doctest::Approx(g.derivative(0, x) / 2.0).epsilon(1e-13));
  }
}

TEST_CASE("support motion: refusals name the key, and the CSV file and line") {
  Sandbox box;
  box.write("r.csv", "t,d,v,a\n0,0,0,0\n1,0.5,1,0\n2,1,0.5,0\n");
  box.write("short.csv", "t,v\n0,0\n1,1\n");
  box.write("late.csv", "t,v\n0,0\n1.5,1\n2,0\n");
  const std::string head = R"({ type = "displacement_record", file = "r.csv", )";
  auto refused = [&](const std::string& value, const std::string& needle, double t_end = 1.0) {
    const std::string e = error_in(box, scene_with(value, t_end));
    CAPTURE(value);
    CAPTURE(e);
    CHECK(has(e, "bad.toml:"));
    CHECK(has(e, needle));
  };
  refused(head + R"(displacement = "d" })", "constraint[1].value: a displacement record needs");
  refused(head + R"(displacement = "d", velocity = "v" })", "or its acceleration alone");
  refused(head + R"(acceleration = "a" })", "constraint[1].value.baseline: an acceleration");
  refused(head + R"(acceleration = "a", baseline = "quadratic" })", "unknown baseline 'quadratic'");
  refused(head + R"(displacement = "d", velocity = "v", acceleration = "a", baseline = "none" })",
          "constraint[1].value.baseline: applies to an acceleration integrated twice");
  refused(head + R"(displacement = "d", velocity = "w", acceleration = "a" })",
          "constraint[1].value.file: ");
  refused(head + R"(displacement = "d", velocity = "v", acceleration = "a", column = "d" })",
          "constraint[1].value.column: unknown key");
  refused(
      R"({ type = "displacement_record", displacement = "d", velocity = "v", acceleration = "a" })",
      "constraint[1].value.displacement: names no file");
  // The three parts must share their sample times: the file and line of the first that differs.
  refused(
      head +
          R"(displacement = "d", velocity = { file = "late.csv", column = "v" }, acceleration = "a" })",
      "constraint[1].value.velocity: late.csv:3: the velocity record's sample 2 is at t = 1.5");
  refused(
      head +
          R"(displacement = "d", velocity = "v", acceleration = { file = "short.csv", column = "v" } })",
      "constraint[1].value.acceleration: short.csv:");
  // Non-increasing times: the CSV reader's refusal, with the part's file key.
  box.write("back.csv", "t,d,v,a\n0,0,0,0\n1,0,0,0\n0.5,0,0,0\n");
  refused(
      R"({ type = "displacement_record", file = "back.csv", displacement = "d", velocity = "v", acceleration = "a" })",
      "back.csv:4: the time 0.5 is not after");
  // A record that ends while moving, before t_end: the support would stop at once.
  refused(head + R"(displacement = "d", velocity = "v", acceleration = "a" })",
          "ends at t = 2, before t_end = 3, while moving (velocity 0.5", 3.0);
  // One that ends at rest is held there.
  box.write("rest.csv", "t,d,v,a\n0,0,0,0\n1,0.5,1,0\n2,1,0,0\n");
  CHECK(
      error_in(
          box,
          scene_with(
              R"({ type = "displacement_record", file = "rest.csv", displacement = "d", velocity = "v", acceleration = "a" })",
              3.0)) == "");
  // Not a load, not a ground acceleration, not a prescribed velocity.
  const std::string triple = head + R"(displacement = "d", velocity = "v", acceleration = "a" })";
  const std::string load = condyn::test::replace(
      scene_with("0.0"), "[solve]", "[[load]]\ndof = \"u\"\nvalue = " + triple + "\n[solve]");
  CHECK(has(error_in(box, load), "load[1].value: a displacement record prescribes a displacement"));
  const std::string ground = condyn::test::replace(
      scene_with("0.0"), "[solve]",
      "[ground_motion]\ninfluence = { u = 1.0 }\nacceleration = " + triple + "\n[solve]");
  CHECK(has(error_in(box, ground), "a displacement record prescribes a displacement, not a force"));
  const std::string velocity = condyn::test::replace(scene_with(triple), "terms = { s = 1.0 }",
                                                     "terms = { s = 1.0 }\nlevel = \"velocity\"");
  CHECK(has(error_in(box, velocity), "it is the right-hand side of a position-level constraint"));
}

}  // namespace test_support_motion
