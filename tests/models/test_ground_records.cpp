// Issue 42, item 1: a ground motion record's peak in the run's summary, and warnings when its name
// says g but its scale is not g (a record in g run without a scale acted 9.81 times too small;
// scale = 981, cm/s² in an SI scene, moved a roof by 13 m), or when an SI peak exceeds 5 g
// (models/assembly/ground_records.hpp).
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "models/assembly/build_model.hpp"
#include "models/assembly/ground_records.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_ground_records {

using condyn::test::replace;
using condyn::test::Sandbox;

namespace {

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TimeTerm table_term(std::vector<double> times, std::vector<double> values, double scale) {
  auto table = std::make_shared<TimeTable>();
  table->file = "r.csv";
  table->column = "a";
  table->times = std::move(times);
  table->values = std::move(values);
  TimeTerm term;
  term.kind = TimeTerm::Kind::table;
  term.amplitude = scale;
  term.table = std::move(table);
  return term;
}

/// One storey in SI (2e5 kg, 3e8 N/m) under the El Centro 1940 NS record of models/scenes/data
/// (in g, peak 0.31882 g at t = 2.02 s by its header), 5 s of it.
std::string storey(const std::string& acceleration, bool si) {
  const std::string record =
      std::string(CONDYN_SOURCE_DIR) + "/models/scenes/data/el_centro_1940_ns.csv";
  return std::string(si ? "units = \"SI\"\n" : "") + R"([model]
type = "matrix"
dofs = ["u"]
mass = [[2e5]]
stiffness = [[3e8]]
[ground_motion]
influence = { u = 1.0 }
acceleration = { type = "table", file = ")" +
         record + "\", " + acceleration + R"( }
[solve]
t_end = 5.0
output_step = 0.1
)";
}

BuildReport report_of(const Sandbox& box, const std::string& scene) {
  BuildReport report;
  (void)build_model(parse_scene_file(box.write("scene.toml", scene).string()), report);
  return report;
}

}  // namespace

TEST_CASE("ground records: which names say g") {
  for (const char* yes : {"acceleration_g", "acc (g)", "PGA-G", "g", "a.g", "G_ns"}) {
    CAPTURE(yes);
    CHECK(name_says_g(yes));
  }
  for (const char* no : {"gal", "deg", "avg", "acceleration", "el_centro_1940_ns", "cm_s2", ""}) {
    CAPTURE(no);
    CHECK_FALSE(name_says_g(no));
  }
}

TEST_CASE("ground records: which scales are g") {
  // SI: within 3 % of 9.80665 (9.8, 9.81 and 10 written for g), nothing else.
  for (double s : {9.80665, 9.81, 9.8, 10.0}) CHECK(scale_is_g(s, true));
  for (double s : {1.0, 981.0, 0.0981, 32.2, -9.81}) CHECK_FALSE(scale_is_g(s, true));
  // Units not given: g per s² in m, cm, mm, ft or in.
  for (double s : {9.81, 981.0, 9806.65, 32.2, 386.1}) CHECK(scale_is_g(s, false));
  for (double s : {1.0, 100.0, 0.0981}) CHECK_FALSE(scale_is_g(s, false));
}

TEST_CASE("ground records: the peak over [0, t_end] lies at a sample or an end") {
  const TimeTerm term = table_term({0.0, 1.0, 2.0, 3.0}, {0.0, 2.0, -3.0, 1.0}, 2.0);
  RecordPeak p = record_peak(term, 10.0);
  CHECK(p.value == -6.0);  // 2 × −3, exact
  CHECK(p.t == 2.0);
  // Cut at t_end = 1.5 (between samples, f = 2 × (−0.5) there): the peak 4 at t = 1.
  p = record_peak(term, 1.5);
  CHECK(p.value == 4.0);
  CHECK(p.t == 1.0);
  // Cut at 1.9: f(1.9) = 2 × (2 − 0.9 × 5) = −5 beats 4, at t_end itself.
  p = record_peak(term, 1.9);
  CHECK(p.t == 1.9);
  CHECK(std::abs(p.value + 5.0) <= 8 * 5.0 * 2.2e-16);  // the interpolation's roundoff
  // A record that starts after t = 0 on a nonzero value acts from t = 0 at it.
  p = record_peak(table_term({1.0, 2.0}, {-3.0, 1.0}, 1.0), 5.0);
  CHECK(p.value == -3.0);
  CHECK(p.t == 0.0);
}

TEST_CASE("ground records: El Centro's peak in the summary, in g when the scene is SI") {
  Sandbox box;
  // Its header: peak 0.31882 g at t = 2.02 s; times 9.81 = 3.1276 m/s².
  BuildReport r = report_of(box, storey("scale = 9.81", true));
  REQUIRE(r.ground_records.size() == 1);
  CHECK(has(r.ground_records[0],
            "el_centro_1940_ns.csv:acceleration_g, 1559 samples)*9.81: peak "
            "3.13 m/s^2 (0.319 g) at t = 2.02 s"));
  CHECK(r.warnings.empty());
  // Units not given: the scene's units, no g.
  r = report_of(box, storey("scale = 9.81", false));
  REQUIRE(r.ground_records.size() == 1);
  CHECK(has(r.ground_records[0], ": peak 3.13 at t = 2.02 (the scene's units"));
  CHECK(r.warnings.empty());
}

TEST_CASE("ground records: a record in g without its scale, or with 981, is warned of") {
  Sandbox box;
  // No scale: the record acts in g as if in m/s², 9.81 times too small; SI or not.
  for (bool si : {true, false}) {
    CAPTURE(si);
    const BuildReport r = report_of(box, storey("column = \"acceleration_g\"", si));
    REQUIRE(r.warnings.size() == 1);
    CHECK(has(r.warnings[0], "ground_motion.acceleration: 'acceleration_g' says the record "));
    CHECK(has(r.warnings[0], "el_centro_1940_ns.csv is in g, but its scale 1 is not g "));
  }
  // 981 (g in cm/s²) in an SI scene: a warning of the scale, and one of the peak (31.3 g).
  BuildReport r = report_of(box, storey("scale = 981.0", true));
  REQUIRE(r.warnings.size() == 2);
  CHECK(has(r.warnings[0],
            "its scale 981 is not g in m/s^2 (9.80665, the scene being SI): the "
            "record acts 100 times as large as its values in g; give scale = "
            "9.81"));
  CHECK(has(r.warnings[1], "peaks at 313 m/s^2 (31.9 g) at t = 2.02 s, beyond 5 g"));
  // Without units, 981 is g in cm/s²: a consistent scene in centimetres, nothing to say.
  CHECK(report_of(box, storey("scale = 981.0", false)).warnings.empty());
  // A name that says nothing of g: an SI peak beyond 5 g is warned of all the same (20 × 0.319).
  r = report_of(box, storey("scale = 9.81", true));
  CHECK(r.warnings.empty());
  box.write("a.csv", "t,a\n0,0\n1,60.0\n5,0\n");
  r = report_of(
      box, replace(storey("scale = 1.0", true),
                   std::string(CONDYN_SOURCE_DIR) + "/models/scenes/data/el_centro_1940_ns.csv",
                   "a.csv"));
  REQUIRE(r.warnings.size() == 1);
  CHECK(has(r.warnings[0], "peaks at 60 m/s^2 (6.12 g) at t = 1 s, beyond 5 g"));
}

TEST_CASE("units: only SI is a unit system the scene can name") {
  Sandbox box;
  std::string error;
  try {
    (void)parse_scene_file(
        box.write("scene.toml", replace(storey("scale = 9.81", true), "\"SI\"", "\"imperial\""))
            .string());
  } catch (const SceneError& e) {
    error = e.what();
  }
  CAPTURE(error);
  CHECK(has(error, "scene.toml:1: units: 'imperial' is not a unit system condyn knows"));
}

}  // namespace test_ground_records
