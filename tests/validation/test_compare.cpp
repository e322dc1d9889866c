// condyn compare: the sweep, its reference, failures recorded as data, and the output files.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "dae/formulations/penalty_ode.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "src/reports/compare_output.hpp"
#include "src/reports/report_format.hpp"
#include "tests/scene_text.hpp"
#include "validation/references/embedded_scenes.hpp"
#include "validation/studies/compare.hpp"

using namespace condyn;

namespace test_compare {

namespace {

CompareOptions small_options() {
  CompareOptions o;
  o.tolerances = {1e-4, 1e-8};
  o.repeats = 2;
  o.schemes = {Scheme::elimination, Scheme::ggl, Scheme::penalty};
  o.baumgarte_factors = {1.0, 10.0};
  o.baumgarte_study = true;
  return o;
}

}  // namespace

TEST_CASE("compare: a model whose constraints fix every DOF has a run as its reference") {
  // No modes: the exact modal solution refused it as "the system has no coordinates (M is
  // empty)", and compare failed (a ValueError in Python).
  const SceneSpec spec = parse_scene_text(R"([model]
type = "matrix"
dofs = ["u1", "u2"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
[[constraint]]
name = "a"
terms = { u1 = 1.0 }
[[constraint]]
name = "b"
terms = { u2 = 1.0 }
value = { type = "harmonic", amplitude = 0.1, omega = 2.0 }
[initial]
velocity = { u2 = 0.2 }
[solve]
t_end = 1.0
output_step = 0.25
)",
                                          "fixed.toml");
  CompareOptions o;
  o.tolerances = {1e-6};
  o.repeats = 1;
  o.schemes = {Scheme::elimination, Scheme::ggl};
  const CompareResult r = run_compare(spec, o);
  CHECK(r.reference_kind == "elimination");
  REQUIRE(r.runs.size() == 2);
  for (const auto& run : r.runs) {
    CAPTURE(std::string(to_string(run.scheme)));
    CHECK(run.ok);
    CHECK(run.error_u < 1e-4);
  }
}

TEST_CASE("compare: wall-time statistics of repeated runs") {
  const WallStatistics odd = wall_statistics({3.0, 1.0, 2.0});
  CHECK(odd.median == 2.0);
  CHECK(odd.min == 1.0);
  CHECK(odd.max == 3.0);
  CHECK(wall_statistics({4.0, 1.0, 3.0, 2.0}).median == 2.5);  // the middle two's mean
  CHECK(wall_statistics({5.0}).median == 5.0);
  CHECK_THROWS_AS((void)wall_statistics({}), std::invalid_argument);
}

TEST_CASE("compare: every scheme and tolerance, errors against the exact solution") {
  const SceneSpec spec = parse_scene_text(embedded_scene("chapter_5_5_1").text, "A");
  const CompareResult r = run_compare(spec, small_options());
  CHECK(r.reference_kind == "exact");
  REQUIRE(r.runs.size() == 3 * 2);
  for (const auto& run : r.runs) {
    CAPTURE(std::string(to_string(run.scheme)));
    CHECK(run.ok);
    CHECK(run.repeats == 2);
    CHECK(run.wall_min > 0.0);  // every repeat was timed
    CHECK(std::isfinite(run.wall_max));
    CHECK(run.steps > 0);
  }
  // Tighter tolerance, smaller error (elimination, GGL); penalty saturates at its 1/w error.
  CHECK(r.runs[1].error_u < r.runs[0].error_u / 100);  // elimination 1e-4 -> 1e-8
  CHECK(r.runs[3].error_u < r.runs[2].error_u / 100);  // ggl
  CHECK(r.runs[5].error_u >
        100 * 1e-8);  // penalty saturates at its 1/w error (~1e-4): above 100 × its rtol 1e-8
  REQUIRE(r.histories.size() == 3);
  CHECK(r.histories[1].ok);
  CHECK(!r.histories[1].trajectory.steps.empty());
  // Asked for, the study runs though baumgarte is not among the schemes: 2 x 2 factors.
  REQUIRE(r.baumgarte_study.size() == 4);

  CompareOptions without_study = small_options();
  without_study.baumgarte_study = false;
  without_study.schemes = {Scheme::baumgarte};
  without_study.tolerances = {1e-4};
  CHECK(run_compare(spec, without_study).baumgarte_study.empty());

  CompareOptions with_baumgarte = small_options();
  with_baumgarte.schemes = {Scheme::baumgarte};
  const CompareResult b = run_compare(spec, with_baumgarte);
  REQUIRE(b.baumgarte_study.size() == 4);
  CHECK(b.baumgarte_study[0].is_default);  // factors (1, 1) come first
  for (const auto& p : b.baumgarte_study) CHECK(p.ok);
}

TEST_CASE("compare: a second run gives the same errors and step counts") {
  const SceneSpec spec = parse_scene_text(embedded_scene("chapter_5_6_2").text, "E");
  CompareOptions o = small_options();
  o.repeats = 1;
  const CompareResult a = run_compare(spec, o), b = run_compare(spec, o);
  REQUIRE(a.runs.size() == b.runs.size());
  for (std::size_t k = 0; k < a.runs.size(); ++k) {
    CHECK(a.runs[k].error_u == b.runs[k].error_u);  // bit for bit: no randomness anywhere
    CHECK(a.runs[k].error_reaction == b.runs[k].error_reaction);
    CHECK(a.runs[k].steps == b.runs[k].steps);
  }
}

// No ';' in a test case's name: CMake's test discovery splits the name there, and the test it
// registered ran no test case (this one failed unseen for sessions).
TEST_CASE("compare: no exact solution means a tight elimination reference, failures are data") {
  // Non-classical damping (a single dashpot coupling two modes): no closed form.
  const char* text = R"([model]
type = "matrix"
dofs = ["a", "b", "c"]
mass = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]]
stiffness = [[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]]
damping = [[0.5, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
[[load]]
dof = "a"
value = 1.0
[[constraint]]
terms = { c = 1.0 }
[solve]
t_end = 2.0
output_step = 0.5
)";
  const SceneSpec spec = parse_scene_text(text, "nonclassical");
  CompareOptions o = small_options();
  o.schemes = {Scheme::elimination, Scheme::penalty};
  const CompareResult r = run_compare(spec, o);
  CHECK(r.reference_kind == "elimination");
  CHECK(r.reference_description.find("no exact solution") != std::string::npos);
  // c has no mass: elimination makes it a slave, penalty holds it by its spring; both run.
  REQUIRE(r.runs.size() == 4);
  for (const auto& run : r.runs) CHECK_MESSAGE(run.ok, run.message);
  // A run beyond its budget is a failed run with its reason, and the sweep goes on.
  o.max_steps = 5;
  const CompareResult budget = run_compare(spec, o);
  CHECK(budget.reference_kind == "elimination");
  REQUIRE(budget.runs.size() == 4);
  for (const auto& run : budget.runs) {
    CHECK_FALSE(run.ok);
    CHECK_MESSAGE(run.message.find("step budget") != std::string::npos, run.message);
  }
}

TEST_CASE("compare: when the tight GGL run fails another scheme gives the reference") {
  // The pendulum of models/scenes at --tolerances 1e-11, GGL's atol_mu set below the constraint
  // rows' roundoff (1e-20; the floor is 1.4e-14 there, docs/schemes.md): GGL at rtol 1e-13 fails,
  // as it did with the derived tolerance before the floor, and compare ended with "no reference
  // solution" though projection and index1 run it. Now the next scheme that applies gives it, and
  // the description says what failed. Over 1 s of the scene's 10 (GGL fails on its first steps;
  // the case took 18 s under the sanitizers over 10 s).
  SceneSpec spec =
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/pendulum.toml");
  spec.solve.atol_mu = 1e-20;
  spec.solve.t_end = 1.0;
  CompareOptions o;
  o.tolerances = {1e-11};
  o.repeats = 1;
  o.schemes = {Scheme::index1};
  const CompareResult r = run_compare(spec, o);
  CHECK(r.reference_kind == "projection");
  CHECK(r.reference_description.find("projection at rtol 1.0e-13") != std::string::npos);
  CHECK_MESSAGE(r.reference_description.find("failed: ggl: ") != std::string::npos,
                r.reference_description);
  REQUIRE(r.runs.size() == 1);
  CHECK_MESSAGE(r.runs[0].ok, r.runs[0].message);
  // index1 at rtol 1e-11 against projection at 1e-13 (measured 2.4e-10 over 1 s, 4.5e-8 over the
  // scene's 10 s).
  CHECK(r.runs[0].error_u < 1e-6);
}

TEST_CASE("compare: a run that takes long reports its progress under its own name") {
  // A conical pendulum in steady rotation at atol 1e-13 crawls under projection (steps of 3e-7
  // s); `condyn compare` without a budget ran for minutes with no hint of which run. Each run's
  // progress now comes through options.progress, led by its place in
  // the sweep. Here with a 3 s budget per run: a line at 2 s, then the failure. (compare keeps
  // the scene's atol/rtol: 1e-15/1e-8 runs at 1e-13/1e-6. At 1e-11/1e-6 it crawled too until
  // the KKT factorizations moved to KLU: now 9,197 steps.)
  const SceneSpec spec =
      parse_scene_text(test::conical_pendulum_scene(60.0, 10.0, 1.0, 1e-15), "conical");
  CompareOptions o;
  o.tolerances = {1e-6};
  o.repeats = 1;
  o.schemes = {Scheme::projection};
  o.max_wall_time = 3.0;
  std::vector<std::string> lines;
  o.progress = [&lines](const std::string& line) { lines.push_back(line); };
  const CompareResult result = run_compare(spec, o);
  REQUIRE(result.runs.size() == 1);
  CHECK_FALSE(result.runs[0].ok);
  CHECK(result.runs[0].message.find("wall-time budget") != std::string::npos);
  bool running = false;
  for (const auto& line : lines) {
    running = running || line.rfind("[1/1] projection rtol 1.0e-06: running, t = ", 0) == 0;
  }
  CHECK(running);
  CHECK(lines.back().find("[1/1] projection rtol 1.0e-06: FAILED") == 0);
}

TEST_CASE("compare: the scene's own budget does not bound the reference") {
  // [solve] max_steps = 450 on the pendulum: the runs at rtol 1e-4 and 1e-6 fit in it, the
  // tight references (ggl, projection, index1 at 1e-8) did not, and compare failed with "no
  // reference solution", though --max-steps exempts the reference.
  const std::string text = test::pendulum_scene(
      "t_end = 2.0\noutput_step = 0.01\nrtol = 1e-8\natol = 1e-10\nmax_steps = 450\n");
  CompareOptions o;
  o.tolerances = {1e-4, 1e-6};
  o.repeats = 1;
  o.schemes = {Scheme::ggl};
  const CompareResult r = run_compare(parse_scene_text(text, "budget"), o);
  CHECK(r.reference_kind == "ggl");
  REQUIRE(r.runs.size() == 2);
  for (const auto& run : r.runs) CHECK_MESSAGE(run.ok, run.message);  // within 450 steps
}

TEST_CASE("compare: the output files follow validation/compare-output.md") {
  const SceneSpec spec = parse_scene_text(embedded_scene("chapter_5_6_2").text, "E");
  CompareOptions o = small_options();
  o.schemes = {Scheme::elimination, Scheme::baumgarte};
  const CompareResult r = run_compare(spec, o);
  const auto dir = std::filesystem::temp_directory_path() /
                   ("condyn_compare_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  write_compare_files(dir.string(), r);
  auto slurp = [&](const char* name) {
    std::ifstream in(dir / name);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const std::string runs = slurp("runs.csv");
  CHECK(
      runs.rfind("scheme,rtol,atol,status,error_u,error_v,error_reaction,max_drift_position,"
                 "max_drift_velocity,final_drift_position,final_drift_velocity,steps,"
                 "residual_evals,jacobian_evals,newton_failures,error_test_failures,"
                 "wall_median_s,wall_min_s,wall_max_s,repeats,message,mescd_u,mescd_v,energy_error,"
                 "error_target,error_ratio,over_tolerance\n",
                 0) == 0);
  CHECK(std::count(runs.begin(), runs.end(), '\n') == 1 + 4);
  const std::string json = slurp("runs.json");
  CHECK(json.find("\"reference\": {\"kind\": \"exact\"") != std::string::npos);
  CHECK(json.find("\"drift_rtol\": ") != std::string::npos);
  CHECK(slurp("drift_baumgarte.csv").rfind("t,drift_position,drift_velocity\n", 0) == 0);
  CHECK(slurp("history_elimination.csv").rfind("t,lambda_mfc1,lambda_mfc2,lambda_mfc3,", 0) == 0);
  const std::string study = slurp("baumgarte_study.csv");
  CHECK(study.rfind("alpha,beta,default,status,max_drift_position,max_drift_velocity,steps,"
                    "wall_s,error_u\n",
                    0) == 0);
  // Every study point ran and has its error against the exact reference (the last field).
  std::istringstream points(study);
  std::string line;
  std::getline(points, line);
  int rows = 0;
  while (std::getline(points, line)) {
    CAPTURE(line);
    const double error = std::stod(line.substr(line.rfind(',') + 1));
    CHECK(error > 0.0);
    CHECK(error < 1e-2);
    ++rows;
  }
  CHECK(rows == 4);  // small_options: factors {1, 10} squared
  // The reference's multipliers at the output times, for the multiplier figure.
  CHECK(slurp("history_reference.csv").rfind("t,lambda_mfc1,lambda_mfc2,lambda_mfc3", 0) == 0);
  CHECK(json.find("\"histories\": {\"elimination\": {\"status\": \"ok\", \"t_reached\": ") !=
        std::string::npos);
  CHECK(slurp("summary.txt").find("reference: exact modal solution") != std::string::npos);

  // A second comparison into the same folder leaves none of the first's files its figures would
  // draw: only GGL's drift and history now, the user's own files kept.
  { std::ofstream(dir / "notes.txt") << "mine\n"; }
  CompareOptions g = small_options();
  g.schemes = {Scheme::ggl};
  g.baumgarte_study = false;
  write_compare_files(dir.string(), run_compare(spec, g));
  for (const char* gone : {"drift_baumgarte.csv", "history_baumgarte.csv", "drift_elimination.csv",
                           "history_elimination.csv", "baumgarte_study.csv"}) {
    CAPTURE(gone);
    CHECK_FALSE(std::filesystem::exists(dir / gone));
  }
  CHECK(std::filesystem::exists(dir / "drift_ggl.csv"));
  CHECK(std::filesystem::exists(dir / "history_ggl.csv"));
  CHECK(slurp("notes.txt") == "mine\n");
  std::filesystem::remove_all(dir);
}

TEST_CASE("plot_compare.py draws its figures from a compare folder of an older format") {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("condyn_plot_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::copy(fs::path(CONDYN_SOURCE_DIR) / "validation" / "sample_compare", dir);
  // Through the same entry point compare uses; the test command installs python3-matplotlib.
  const std::string note = draw_compare_plots(dir.string());
  CAPTURE(note);
  CHECK(note.rfind("plots written", 0) == 0);
  const auto head = [](const fs::path& p) {  // a file's first four bytes
    std::ifstream f(p, std::ios::binary);
    std::string bytes(4, '\0');
    f.read(bytes.data(), 4);
    return bytes;
  };
  // The sample has no history_reference.csv and no study errors: the multipliers are drawn
  // against the elimination run, the study without its error panel.
  for (const char* plot :
       {"work_precision", "error_steps", "drift", "multipliers", "baumgarte_study"}) {
    CAPTURE(plot);
    CHECK(fs::file_size(dir / (std::string(plot) + ".png")) > 10000);
    CHECK(fs::file_size(dir / (std::string(plot) + ".pdf")) > 5000);
    // what the names promise: a PNG's signature, a PDF's header
    CHECK(head(dir / (std::string(plot) + ".png")) == "\x89PNG");
    CHECK(head(dir / (std::string(plot) + ".pdf")) == "%PDF");
  }
  std::ifstream log(dir / "plots.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  CHECK(text.find("skipped") == std::string::npos);
  CHECK(text.find("failed") == std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("compare against a reference at rest: errors relative to the run's own scale") {
  // The period-2 pendulum is back at rest at t = 2: its reference velocity is 0, and a velocity
  // error relative to it was 0/0 ("non-finite error against the reference" for every run).
  SceneSpec spec =
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/pendulum_period2.toml");
  spec.solve.t_end = 2.0;
  CompareOptions o;
  o.tolerances = {1e-6, 1e-9};
  o.repeats = 1;
  o.schemes = {Scheme::ggl};
  const CompareResult r = run_compare(spec, o);
  REQUIRE(r.runs.size() == 2);
  for (const auto& run : r.runs) {
    CAPTURE(run.message);
    CHECK(run.ok);
    CHECK(std::isfinite(run.error_v));
  }
  CHECK(r.runs[1].error_v < r.runs[0].error_v / 100);  // three decades of rtol, at least two
}

TEST_CASE("compare on a published benchmark: digits per run under every scheme asked for") {
  namespace fs = std::filesystem;
  const SceneSpec spec =
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/car_axis.toml");
  CompareOptions o;
  o.tolerances = {1e-4, 1e-8};
  o.repeats = 1;
  o.schemes = {Scheme::elimination, Scheme::ggl, Scheme::index2, Scheme::penalty};
  const CompareResult r = run_compare(spec, o);
  CHECK(r.reference_kind == "published");
  CHECK(r.trusted_digits_u == 10);
  // Every scheme asked for applies: elimination by coordinate partitioning, penalty as the
  // augmented Lagrangian (docs/schemes.md).
  CHECK(r.skipped.empty());
  REQUIRE(r.runs.size() == 4 * 2);
  for (const auto& run : r.runs) {
    CAPTURE(std::string(to_string(run.scheme)));
    CAPTURE(run.rtol);
    REQUIRE(run.ok);
    // mescd and the relative error measure the same deviation: digits ~ -log10(error) within the
    // spread of the components' scales (car axis positions 0.05 to 1).
    CHECK(run.mescd_u == doctest::Approx(-std::log10(run.error_u)).epsilon(0.5));
    CHECK(std::isfinite(run.mescd_v));
  }
  // Four decades of tolerance buy at least two digits (observed: GGL 3.3 -> 7.0), under each
  // scheme (runs by scheme, then tolerance).
  CHECK(r.runs[1].mescd_u > r.runs[0].mescd_u + 2.0);
  CHECK(r.runs[3].mescd_u > r.runs[2].mescd_u + 2.0);
  CHECK(r.runs[5].mescd_u > r.runs[4].mescd_u + 2.0);
  CHECK(r.runs[7].mescd_u > r.runs[6].mescd_u + 2.0);

  const fs::path dir =
      fs::temp_directory_path() / ("condyn_compare_published_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  write_compare_files(dir.string(), r);
  std::ifstream json(dir / "runs.json");
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  CHECK(text.find("\"kind\": \"published\"") != std::string::npos);
  const std::string note = draw_compare_plots(dir.string());
  CAPTURE(note);
  CHECK(note.rfind("plots written", 0) == 0);
  CHECK(fs::file_size(dir / "work_precision.png") > 1000);
  fs::remove_all(dir);

  // Only schemes the scene refuses: elimination on the sleigh's nonholonomic row.
  o.schemes = {Scheme::elimination};
  CHECK_THROWS_AS((void)run_compare(parse_scene_file(std::string(CONDYN_SOURCE_DIR) +
                                                     "/models/scenes/chaplygin_sleigh.toml"),
                                    o),
                  SchemeNotApplicable);
}

TEST_CASE("compare: quantities zero at every output row are measured against the whole run") {
  // The period-2 pendulum sampled once a swing (output_step 1) is at a turning point at every
  // row: its rod force, velocity and kinetic energy are zero there, and errors relative to their
  // largest value over the rows read 1.5e2 (reactions), 8e-4 (velocities) and 4.4e4 (energy) at
  // rtol 1e-7 under GGL while the positions were right to 2.9e-6. Against their largest values
  // over the whole run (the reference sampled four times per output step) every error is of
  // the positions' order: the bound is GGL's largest global error over rtol on the example
  // scenes from rtol 1e-3 to 1e-10 (8e2, the inclined roller; validation/compare-output.md).
  constexpr double kGlobalErrorOverRtol = 1e3;
  SceneSpec spec =
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/pendulum_period2.toml");
  spec.solve.output_step = 1.0;
  CompareOptions o;
  o.tolerances = {1e-7};
  o.repeats = 1;
  o.schemes = {Scheme::ggl};
  for (double t_end : {19.0, 20.0}) {  // a tight GGL reference at 19, the published state at 20
    CAPTURE(t_end);
    spec.solve.t_end = t_end;
    const CompareResult r = run_compare(spec, o);
    CHECK(r.reference_kind == (t_end == 20.0 ? "published" : "ggl"));
    REQUIRE(r.runs.size() == 1);
    const RunRecord& run = r.runs[0];
    REQUIRE(run.ok);
    CHECK(run.error_u < kGlobalErrorOverRtol * run.rtol);
    CHECK(run.error_v < kGlobalErrorOverRtol * run.rtol);
    if (t_end == 19.0) CHECK(run.error_reaction < kGlobalErrorOverRtol * run.rtol);
    CHECK(run.energy_error < kGlobalErrorOverRtol * run.rtol);
    // The scales are the run's size, each at the bottom of the swing (unit mass and length,
    // g = (2 K(1/sqrt 2))^2 = 13.75): |u'| = sqrt(2 g) = 5.24, the rod force 3 m g = 41.25 and
    // the kinetic energy m g = 13.75, sampled within 1 % by four rows a swing; |u| = L = 1.
    constexpr double kSampled = 0.01;
    const double g = std::pow(2.0 * 1.8540746773013719, 2);  // K(1/sqrt 2), DLMF 19.20.2
    CHECK(r.error_scales.displacement == doctest::Approx(1.0).epsilon(kSampled));
    CHECK(r.error_scales.velocity == doctest::Approx(std::sqrt(2.0 * g)).epsilon(kSampled));
    CHECK(r.error_scales.energy == doctest::Approx(g).epsilon(kSampled));
    if (t_end == 19.0) CHECK(r.error_scales.reaction == doctest::Approx(3.0 * g).epsilon(kSampled));
  }
}

TEST_CASE("compare: one rule for the drift fit of every scheme") {
  // The pendulum over 10 s (about 4 swings): GGL's velocities chatter about zero and counted 10
  // or more sign changes, so its drift was assessed for a growth law where index1's, counting
  // 8 oscillations, was refused as too short a run. The motion's oscillations are counted once.
  const SceneSpec spec =
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/pendulum.toml");
  CompareOptions o;
  o.tolerances = {1e-4};
  o.repeats = 1;
  o.schemes = {Scheme::ggl, Scheme::index1};
  const CompareResult r = run_compare(spec, o);
  REQUIRE(r.histories.size() == 2);
  for (const auto& h : r.histories) {
    CAPTURE(std::string(to_string(h.scheme)));
    CAPTURE(h.growth.reason);
    REQUIRE(h.ok);
    CHECK_FALSE(h.growth.fit);
    CHECK(h.growth.reason.find("oscillations of the motion") != std::string::npos);
  }
  CHECK(r.histories[0].growth.reason == r.histories[1].growth.reason);
}

TEST_CASE("compare: the error target of every scheme, penalty's from its weight") {
  SceneSpec spec = parse_scene_text(embedded_scene("chapter_5_6_2").text, "E");
  CompareOptions o;
  o.tolerances = {1e-8};
  o.repeats = 1;
  o.schemes = {Scheme::ggl, Scheme::penalty};
  o.baumgarte_study = false;
  o.mark_factor = 100.0;
  const CompareResult r = run_compare(spec, o);
  REQUIRE(r.runs.size() == 2);
  CHECK(r.runs[0].error_target == 1e-8);
  CHECK(r.runs[1].error_target == kPenaltyAccuracy);  // the default weight's
  for (const auto& run : r.runs) {
    CAPTURE(std::string(to_string(run.scheme)));
    REQUIRE(run.ok);
    const double worst = std::max({run.error_u, run.error_v, run.error_reaction});
    CHECK(run.error_ratio == worst / run.error_target);
    CHECK(run.over_tolerance == (run.error_ratio > o.mark_factor));
  }
  // Penalty's reactions ring at its springs' frequency (11 % of their size, docs/schemes.md):
  // 1e3 times its target, beyond the factor 100; GGL's worst error is 40 times rtol.
  CHECK(r.runs[1].over_tolerance);
  CHECK_FALSE(r.runs[0].over_tolerance);
  CHECK(r.over_tolerance_runs() == 1);
  // Ten times the default weight: a target ten times smaller (errors shrink like 1/w).
  BuildReport report;
  const Model model = build_model(spec, report);
  spec.solve.penalty_weight = 10.0 * penalty_weights(model, spec.solve).position;
  o.schemes = {Scheme::penalty};
  const CompareResult heavy = run_compare(spec, o);
  REQUIRE(heavy.runs.size() == 1);
  CHECK(heavy.runs[0].error_target == doctest::Approx(kPenaltyAccuracy / 10.0));
  CHECK_THROWS_AS(
      [&] {
        CompareOptions bad = o;
        bad.mark_factor = 0.5;
        bad.validate();
      }(),
      std::invalid_argument);
}

TEST_CASE("compare's table keeps every column apart whatever the width of its values") {
  // 184040 Jacobian evaluations beside 5781.76 ms of wall time read "1840405781.76".
  CompareResult result;
  result.scene_name = "wide";
  result.reference_kind = "exact";
  result.scale_source = "the reference";
  RunRecord r;
  r.scheme = Scheme::projection;
  r.rtol = 1e-5;
  r.ok = true;
  r.error_u = r.error_v = r.error_reaction = 1e-3;
  r.error_target = 1e-5;
  r.error_ratio = 100.0;
  r.steps = 123456789;
  r.residual_evals = 1234567890;
  r.jacobian_evals = 184040;
  r.wall_median = r.wall_min = r.wall_max = 5.78176;
  result.runs.push_back(r);
  RunRecord failed = r;
  failed.ok = false;
  failed.message = "step budget exhausted";
  result.runs.push_back(failed);
  std::ostringstream out;
  print_compare_table(out, result);
  const std::string text = out.str();
  CAPTURE(text);
  // Each figure is a word of its own.
  std::istringstream words(text);
  std::vector<std::string> all{std::istream_iterator<std::string>(words), {}};
  for (const char* figure : {"123456789", "1234567890", "184040", "5781.76"}) {
    CAPTURE(figure);
    CHECK(std::find(all.begin(), all.end(), figure) != all.end());
  }
  CHECK(text.find("FAILED: step budget exhausted") != std::string::npos);
}

TEST_CASE("text tables: columns as wide as their widest cell, a gap between any two") {
  TextTable table({"a", "bb"}, "  ");
  table.add_row({"12345", "x"});
  table.add_row({"≥1", "y"});  // two characters, four bytes
  table.add_row({"only: a message that spans the columns after it"});
  std::ostringstream out;
  table.print(out);
  CHECK(out.str() ==
        "  a      bb\n"
        "  12345  x\n"
        "  ≥1     y\n"
        "  only: a message that spans the columns after it\n");
}

}  // namespace test_compare
