// Issue 13, item 1: tabulated time functions (scene-format.md, "Time functions from data"). The
// CSV reader and its refusals (each naming the scene's key, the CSV file and its line), piecewise
// linear evaluation, and what a table answers as a TimeFunction (scaled, is_zero, is_constant,
// breakpoints, derivatives), and its refusal as a constraint's right-hand side.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/core/time_table.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_time_table {

using condyn::test::Sandbox;

namespace {

/// Interpolation of binary fractions: weights and products below are exact or within a few ulps
/// of values of order 10.
constexpr double kRoundoff = 8 * std::numeric_limits<double>::epsilon() * 10.0;

const std::string kRecord =
    "# a comment line\n"
    "t, a, b\n"
    "0.0, 1.0, 10.0\n"
    "# comments may stand between rows\n"
    "0.5, 3.0, 20.0\n"
    "\n"
    "1.5, -1.0, 20.0\n";

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// A one-DOF matrix model whose load is `value` (a TOML inline table).
std::string load_scene(const std::string& value) {
  return R"([model]
type = "matrix"
dofs = ["x"]
mass = [[1.0]]
stiffness = [[4.0]]
[[load]]
dof = "x"
value = )" +
         value +
         R"(
[solve]
t_end = 2.0
output_step = 0.5
)";
}

/// The SceneError message of the scene, else "".
std::string scene_error(const Sandbox& box, const std::string& scene) {
  return test::file_build_error(box.write("scene.toml", scene).string());
}

}  // namespace

TEST_CASE("time table: piecewise linear between samples, held outside, columns by name") {
  const TimeTable a = parse_time_table(kRecord, "");
  CHECK(a.column == "a");  // the second column by default, named by the header
  REQUIRE(a.samples() == 3);
  CHECK(a.value(-1.0) == 1.0);  // the first value before the first sample
  CHECK(a.value(0.0) == 1.0);
  CHECK(a.value(0.25) == doctest::Approx(2.0).epsilon(kRoundoff));
  CHECK(a.value(0.5) == 3.0);
  CHECK(a.value(1.0) == doctest::Approx(1.0).epsilon(kRoundoff));
  CHECK(a.value(1.5) == -1.0);
  CHECK(a.value(7.0) == -1.0);  // the last value after the last sample
  // Right-continuous slopes, 0 outside the samples.
  CHECK(a.slope(-0.1) == 0.0);
  CHECK(a.slope(0.0) == 4.0);
  CHECK(a.slope(0.5) == -4.0);
  CHECK(a.slope(1.5) == 0.0);
  CHECK(a.max_abs_value == 3.0);
  CHECK(a.max_abs_slope == 4.0);

  const TimeTable b = parse_time_table(kRecord, "b");
  CHECK(b.column == "b");
  CHECK(b.value(0.25) == doctest::Approx(15.0).epsilon(kRoundoff));
  CHECK(b.value(1.0) == 20.0);

  // Without a header: the second column, named "column 2"; a '+' sign and CRLF lines pass.
  const TimeTable bare = parse_time_table("0, 2\r\n1, +4\r\n", "");
  CHECK(bare.column == "column 2");
  CHECK(bare.value(0.5) == 3.0);
  // Lone CR line ends (a spreadsheet's "CSV (Macintosh)") and quoted header names (R's
  // write.csv) read as the plain file does.
  const TimeTable mac = parse_time_table("t,a,b\r0,1,10\r1,2,20\r", "b");
  CHECK(mac.times.size() == 2);
  CHECK(mac.value(0.5) == 15.0);
  // A UTF-8 byte order mark (Excel's "CSV UTF-8") is no part of the header's first name, nor of
  // the first sample of a file without a header (which was then taken for a header).
  const TimeTable bom = parse_time_table("\xEF\xBB\xBFt,a\n0,1\n1,3\n", "a");
  CHECK(bom.time_column == "t");
  CHECK(bom.value(0.5) == 2.0);
  const TimeTable bom_bare = parse_time_table(
      "\xEF\xBB\xBF"
      "0,1\n1,3\n",
      "");
  CHECK(bom_bare.column == "column 2");
  CHECK(bom_bare.times.size() == 2);
  const TimeTable quoted = parse_time_table("\"t\",\"a\"\n0,1\n1,3\n", "a");
  CHECK(quoted.column == "a");
  CHECK(quoted.value(0.5) == 2.0);
  // Quoting is there so that a name may hold a comma or a quote (RFC 4180: "" is one quote):
  // "acc, g" was split in two cells and listed back as the name asked for.
  const TimeTable comma =
      parse_time_table("\"t\",\"acc, g\",\"say \"\"hi\"\"\"\n0,1,5\n1,3,7\n", "acc, g");
  CHECK(comma.value(0.5) == 2.0);
  CHECK(parse_time_table("\"t\",\"acc, g\",\"say \"\"hi\"\"\"\n0,1,5\n1,3,7\n", "say \"hi\"")
            .value(0.5) == 6.0);
  CHECK_THROWS_WITH_AS((void)parse_time_table("\"t,a\n0,1\n1,3\n", ""),
                       "a double quote opens a cell and none closes it", TimeTableError);
  CHECK_THROWS_WITH_AS((void)parse_time_table("\"t\"x,a\n0,1\n1,3\n", ""),
                       "text follows the closing double quote of a cell", TimeTableError);
}

TEST_CASE("time table: a row index first (R's write.csv, pandas' to_csv) is refused") {
  // Read as time, the index 1, 2, 3 stretched a 0.02 s record fifty-fold and started it at 1.
  for (const char* text : {"\"\",\"t\",\"a\"\n\"1\",0,1\n\"2\",0.02,3\n",  // R
                           ",t,a\n0,0,1\n1,0.02,3\n",                      // pandas
                           "index,time,a\n0,0,1\n1,0.02,3\n",              // named index
                           ",a\n0,1\n1,3\n"}) {  // unnamed first column, no other time column
    CAPTURE(std::string(text));
    CHECK_THROWS_WITH_AS((void)parse_time_table(text, ""),
                         doctest::Contains("the first column holds the time, but it is"),
                         TimeTableError);
  }
  CHECK_THROWS_WITH_AS((void)parse_time_table(",t,a\n0,0,1\n1,0.02,3\n", "a"),
                       doctest::Contains("unnamed and column 2 is 't': a row index"),
                       TimeTableError);
  // Time first under any name, or named t or Time: read as before.
  CHECK(parse_time_table("seconds,a\n0,1\n1,3\n", "").value(0.5) == 2.0);
  CHECK(parse_time_table("Time,a,t2\n0,1,5\n1,3,7\n", "a").value(0.5) == 2.0);
}

TEST_CASE("time table: an interval beyond the double range is refused") {
  // An interval beyond the double range (−1e308 to 1e308) is refused: interpolation across it
  // returned the first value.
  CHECK_THROWS_WITH_AS((void)parse_time_table("t,a\n-1e308,-1\n1e308,1\n", ""),
                       doctest::Contains("their interval overflows the double range"),
                       TimeTableError);
}

TEST_CASE("time table: a time function with a scale, shared samples and no breakpoints") {
  Sandbox box;
  box.write("rec.csv", kRecord);
  const auto spec = parse_scene_file(
      box.write("s.toml", load_scene(R"({ type = "table", file = "rec.csv", scale = 2.0 })"))
          .string());
  const TimeFunction& f = spec.loads.at(0).value;
  REQUIRE(f.terms().size() == 1);
  CHECK(f.has_table());
  CHECK(f.value(0.25) == doctest::Approx(4.0).epsilon(kRoundoff));
  CHECK(f.derivative(1, 0.25) == 8.0);
  CHECK(f.derivative(2, 0.25) == 0.0);
  CHECK(f.describe() == "table(rec.csv:a, 3 samples)*2");
  CHECK(f.breakpoints().empty());  // kinks are not restarts
  CHECK_FALSE(f.is_constant());
  CHECK_FALSE(f.is_zero());
  // scaled() multiplies the scale and shares the samples (a copy costs a pointer).
  const TimeFunction g = f.scaled(-0.5);
  CHECK(g.value(0.25) == doctest::Approx(-2.0).epsilon(kRoundoff));
  CHECK(g.terms()[0].table == f.terms()[0].table);
  CHECK(f.scaled(0.0).is_zero());
  CHECK_THROWS_AS((void)f.antiderivative(), std::invalid_argument);
  CHECK_THROWS_AS((void)f.terms()[0].derivative_term(), std::invalid_argument);
  // Without a scale: describe() omits it; a table of equal values is constant, of zeros zero.
  box.write("flat.csv", "t,z,c\n0,0,2\n1,0,2\n");
  const auto flat = [&](const std::string& column) {
    return parse_scene_file(
               box.write("f.toml", load_scene(R"({ type = "table", file = "flat.csv", column = ")" +
                                              column + "\" }"))
                   .string())
        .loads.at(0)
        .value;
  };
  CHECK(flat("c").describe() == "table(flat.csv:c, 2 samples)");
  CHECK(flat("c").is_constant());
  CHECK_FALSE(flat("c").is_zero());
  CHECK(flat("z").is_zero());
  // The model's loads: 2 * table at the load's DOF.
  const Model model = build_model(spec);
  CHECK(model.applied_forces(1.0)[0] == doctest::Approx(2.0).epsilon(kRoundoff));
}

TEST_CASE("time table: the El Centro record, binary search, describe()") {
  const std::string path =
      std::string(CONDYN_SOURCE_DIR) + "/../shared/reference/ground-motion/el_centro_1940_ns.csv";
  if (!std::filesystem::exists(path)) {
    MESSAGE("skipped: " << path << " is not beside the repository");
    return;
  }
  TimeTable record = read_time_table(path, "acceleration_g");
  record.file = "el_centro.csv";
  REQUIRE(record.samples() == 1559);
  CHECK(record.times.back() == doctest::Approx(31.16).epsilon(1e-15));
  // Its header says: peak |a| = 0.31882 g at t = 2.02 s.
  CHECK(record.max_abs_value == 0.31882);
  CHECK(std::abs(record.value(2.02)) == 0.31882);
  TimeTerm term;
  term.kind = TimeTerm::Kind::table;
  term.amplitude = 9.81;
  term.table = std::make_shared<const TimeTable>(record);
  CHECK(term.describe() == "table(el_centro.csv:acceleration_g, 1559 samples)*9.81");
}

TEST_CASE("time table: bad files are refused with the scene key, the CSV file and its line") {
  Sandbox box;
  const std::string scene = box.path("scene.toml").string();
  const auto error = [&](const std::string& csv, const std::string& column = "") {
    box.write("rec.csv", csv);
    return scene_error(box,
                       load_scene(R"({ type = "table", file = "rec.csv")" +
                                  (column.empty() ? "" : ", column = \"" + column + "\"") + " }"));
  };
  const std::string file = box.path("rec.csv").string();
  const std::string key = scene + ":8: load[1].value.file: " + file;

  CHECK(error(kRecord).empty());
  CHECK(has(error(kRecord, "c"), key + ":2: no column 'c' (the value columns are: a, b)"));
  CHECK(has(error("t,a,a\n0,1,2\n1,2,3\n", "a"), key + ":1: two columns are named 'a'"));
  CHECK(has(error("t,a\n0,1\n0,2\n"), key + ":3: the time 0 is not after the previous"));
  CHECK(has(error("t,a\n0,1\n1,2\n0.5,3\n"), key + ":4: the time 0.5 is not after"));
  CHECK(has(error("t,a\n0,1\n1,x2\n"), key + ":3: the value 'x2' is not a number"));
  // A cell is quoted short and without control bytes (a NUL cut the message off).
  CHECK(has(error("t,a\n0,1\n1," + std::string(100000, 'x') + "\n"),
            key + ":3: the value '" + std::string(40, 'x') + "...' is not a number"));
  CHECK(has(error(std::string("t,a\n0,1\n1,x\0y\n", 13)),
            key + ":3: the value 'x?y' is not a number"));
  CHECK(has(error("t,a\n0,1\n1 s,2\n"), key + ":3: the time '1 s' is not a number"));
  CHECK(
      has(error("t,a\n0,1\n1,1e400\n"), key + ":3: the value '1e400' is out of the double range"));
  CHECK(has(error("t,a\n0,1\n1,nan\n"), key + ":3: the value 'nan' is not finite"));
  CHECK(has(error("t,a\n0,1\ninf,2\n"), key + ":3: the time 'inf' is not finite"));
  CHECK(has(error("t,a\n0,1\n1\n"), key + ":3: has 1 cell(s) but the values are in column 2"));
  // A row longer (or, past the value column, shorter) than the first: a decimal comma shifts
  // the cells, and 1,0,5 would have read as the value 0 at t = 1.
  CHECK(has(error("t,a\n0,1\n1,0,5\n"), key + ":3: has 3 cells, line 1 has 2: every row needs"));
  CHECK(has(error("0,1\n1,0,5\n"), key + ":2: has 3 cells, line 1 has 2"));
  CHECK(has(error("t,a,b\n0,1,2\n1,2\n"), key + ":3: has 2 cells, line 1 has 3"));
  CHECK(has(error("t,a\n0,1\n1,2,\n"), key + ":3: has 3 cells, line 1 has 2"));
  CHECK(has(error("t,a\n0,1\n"), key + ": has 1 sample(s): a table needs at least 2"));
  CHECK(has(error("# only comments\n"), key + ": has 0 sample(s)"));
  CHECK(has(error("t\n0\n"), key + ":1: has 1 column: a table needs time and a column"));
  // Another separator than the comma: the one a spreadsheet used, named with the remedy
  // (issue 42: a semicolon-separated record was reported as "has 1 column" alone).
  CHECK(has(error("t;a\n0;0,5\n1;1,5\n"),
            key + ":1: has 1 column: a table needs time and a column of values; its cells seem "
                  "separated by semicolons (';')"));
  CHECK(has(error("0;1\n1;2\n"), key + ":1: has 1 column: a table needs time and a column of "
                                       "values; its cells seem separated by semicolons"));
  CHECK(has(error("t\ta\n0\t1\n1\t2\n"), "; its cells seem separated by tabs"));
  CHECK(has(error("t a\n0 1\n1 2\n"), "; its cells seem separated by spaces"));
  CHECK(has(error("t,a\n0,1\n1;2\n"), key + ":3: has 1 cell(s) but the values are in column 2; "
                                            "its cells seem separated by semicolons"));
  CHECK(has(error("0,1\n1,2\n", "a"),
            key + ":1: has no header line naming its columns, so no column 'a' (add a header "
                  "line such as t,a)"));
  // A file that is not there, or no regular file.
  CHECK(has(scene_error(box, load_scene(R"({ type = "table", file = "none.csv" })")),
            "load[1].value.file: " + box.path("none.csv").string() + ": cannot open the file"));
  CHECK(has(scene_error(box, load_scene(R"({ type = "table", file = "/dev/zero" })")),
            "/dev/zero: is not a regular file"));
  // A NUL in the name (\u0000 in TOML) would open the file named by what precedes it.
  CHECK(has(scene_error(box, load_scene(R"({ type = "table", file = "ok.csv\u0000x" })")),
            "load[1].value.file: the file name holds a NUL character"));
  // Keys: unknown, missing, empty.
  box.write("ok.csv", kRecord);
  CHECK(has(scene_error(box, load_scene(R"({ type = "table", file = "ok.csv", scal = 2 })")),
            "load[1].value.scal: unknown key (did you mean scale? expected one of: type, file, "
            "column, scale)"));
  CHECK(has(scene_error(box, load_scene(R"({ type = "table" })")),
            "load[1].value.file: missing required key"));
  CHECK(has(scene_error(box, load_scene(R"({ type = "table", file = "ok.csv", column = "" })")),
            "load[1].value.column: must not be empty"));
  CHECK(has(scene_error(box, load_scene(R"({ type = "table", file = "ok.csv", scale = nan })")),
            "load[1].value.scale"));
}

TEST_CASE("time table: refused as a constraint's right-hand side, with the reason") {
  Sandbox box;
  box.write("rec.csv", kRecord);
  const std::string base = R"([model]
type = "matrix"
dofs = ["x", "y"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
[[constraint]]
terms = { x = 1.0 }
value = { type = "table", file = "rec.csv" }
[solve]
t_end = 2.0
output_step = 0.5
)";
  const std::string position = scene_error(box, base);
  CHECK(has(position, "constraint[1].value: a table cannot be a prescribed displacement"));
  CHECK(has(position, "[ground_motion]"));
  const std::string velocity =
      scene_error(box, condyn::test::replace(base, "terms = { x = 1.0 }",
                                             "terms = { x = 1.0 }\nlevel = \"velocity\""));
  CHECK(has(velocity, "constraint[1].value: a table cannot be a prescribed velocity"));
}

TEST_CASE("time table: a ramp of 1e-12 s at t = 0 runs as the step it approximates") {
  // IDA's first step (1e-3 of the first output interval) crossed the ramp with no history, and
  // ten error-test failures did not bring it below the ramp: every scheme failed at t = 0. The
  // first step now stays below half the table's first interval (IntegratorOptions::first_kink).
  Sandbox box;
  box.write("ramp.csv", "t,a\n0,0\n1e-12,1\n2,1\n");
  const auto scene = [](const std::string& value) {
    return test::kTwoMassChainModel + R"([[load]]
dof = "u2"
value = )" +
           value + R"(
[[constraint]]
terms = { u1 = 1.0, u2 = 0.5 }
[solve]
t_end = 1.0
output_step = 0.25
)";
  };
  const SceneSpec step_spec =
      parse_scene_text(scene("{ type = \"step\", amplitude = 10.0 }"), "step.toml");
  const SolveResult step = test::solved(build_model(step_spec), step_spec.solve);
  const SceneSpec ramp_spec = parse_scene_file(
      box.write("ramp.toml", scene("{ type = \"table\", file = \"ramp.csv\", scale = 10.0 }"))
          .string());
  const Model ramp = build_model(ramp_spec);
  const double scale = step.trajectory.u.cwiseAbs().maxCoeff();
  for (const Scheme s : {Scheme::elimination, Scheme::ggl, Scheme::index1}) {
    CAPTURE(to_string(s));
    const SolveResult r = test::solved(ramp, test::under(ramp_spec.solve, s));
    // The ramp differs from the step by 1e-12 s of load; both runs at rtol 1e-8: their global
    // errors (observed 1e-6 of the reactions' 20, 5e-8 relative) bound the difference.
    CHECK((r.trajectory.u - step.trajectory.u).cwiseAbs().maxCoeff() <= 1e-6 * scale);
  }
}

}  // namespace test_time_table
