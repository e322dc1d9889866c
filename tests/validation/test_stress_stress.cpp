// condyn stress as a test tier: the whole suite runs (its long horizons under GGL and projection
// only, suite() below), no run crashes, hangs or reports a
// non-finite number as a result, every break and refusal carries its reason, and the findings
// docs/validation.md reports still hold (each expectation below names the family's observation).
#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "src/reports/report_format.hpp"
#include "src/reports/stress_output.hpp"
#include "validation/studies/stress.hpp"

using namespace condyn;

namespace test_stress_stress {

namespace {

/// The suite as `condyn stress` runs it, but the long horizons only under the two schemes the
/// findings name (GGL and projection): the 1e5 periods under the six others took half the
/// tier's time and are judged nowhere (`condyn stress --families long_horizon` runs them).
const StressResult& suite() {
  static const StressResult result = [] {
    StressOptions o;
    o.threads = 2;
    for (const auto& f : stress_families())
      if (f.name != "long_horizon") o.families.push_back(f.name);
    StressResult all = run_stress(o);
    o.families = {"long_horizon"};
    o.schemes = {Scheme::ggl, Scheme::projection};
    StressResult longest = run_stress(o);
    all.cases.insert(all.cases.end(), longest.cases.begin(), longest.cases.end());
    all.records.insert(all.records.end(), longest.records.begin(), longest.records.end());
    all.wall_seconds += longest.wall_seconds;
    return all;
  }();
  return result;
}

const StressRecord& record(const std::string& family, const std::string& label, Scheme scheme) {
  for (const auto& r : suite().records) {
    if (r.family == family && r.label == label && r.scheme == scheme) return r;
  }
  FAIL("no record " << family << " " << label << " " << to_string(scheme));
  throw std::logic_error("unreachable");
}

}  // namespace

TEST_CASE("stress: the schemes a case runs under, with and without --schemes") {
  StressCase every;  // lists none: every scheme stress runs
  StressCase two;
  two.schemes = {Scheme::projection, Scheme::ggl};
  const std::vector<Scheme> all(std::begin(kSchemes), std::end(kSchemes));
  CHECK(stress_runs(every, {}) == all);
  CHECK(stress_runs(two, {}) == two.schemes);
  // Only those asked for, in the case's order (kSchemes' when it lists none).
  CHECK(stress_runs(every, {Scheme::projection, Scheme::index1}) ==
        std::vector<Scheme>{Scheme::index1, Scheme::projection});
  CHECK(stress_runs(two, {Scheme::ggl, Scheme::index1}) == std::vector<Scheme>{Scheme::ggl});
  CHECK(stress_runs(two, {Scheme::index1}).empty());
}

TEST_CASE("stress: every run ends in a verdict with its reason, never a non-finite result") {
  const auto& result = suite();
  REQUIRE(result.records.size() > 150);
  for (const auto& r : result.records) {
    CAPTURE(r.case_id);
    CAPTURE(std::string(to_string(r.scheme)));
    CAPTURE(r.reason);
    const bool ran = r.status == "holds" || r.status == "inaccurate";
    CHECK((ran || r.status == "failed" || r.status == "refused"));
    if (r.status != "holds") CHECK_FALSE(r.reason.empty());
    if (r.status == "failed") CHECK_FALSE(r.suggestion.empty());
    if (ran) {
      CHECK(r.steps > 0);
      CHECK(std::isfinite(r.max_drift_position));
      CHECK(std::isfinite(r.max_drift_velocity));
      if (r.error) CHECK(std::isfinite(*r.error));
      if (r.energy_error) CHECK(std::isfinite(*r.energy_error));
    }
  }
}

TEST_CASE("stress: the findings docs/validation.md reports") {
  // Stiffness ratio 1e12: elimination holds (observed error 2.4e-7). GGL holds to 1e8; at 1e12
  // whether a run damps the chain's 1e6 rad/s mode or resolves it (steps of 4e-7, out of steps)
  // turns on its step sequence: of 28 variants (R = 1, 2, 3, 5 x 1e12, rtol 1e-7 to 1e-9) 18
  // reach t_end, 16 before Newton corrections kept GGL's constraint rows exact
  // (dae/integrators/stale_correction.hpp), and this one no longer does. Either way it never
  // returns an inaccurate result.
  CHECK(record("stiffness", "R = 1e+12", Scheme::elimination).status == "holds");
  CHECK(record("stiffness", "R = 1e+08", Scheme::ggl).status == "holds");
  const auto& stiffest_ggl = record("stiffness", "R = 1e+12", Scheme::ggl);
  CHECK((
      stiffest_ggl.status == "holds" ||
      (stiffest_ggl.status == "failed" && stiffest_ggl.reason.find("steps") != std::string::npos)));
  // index1 holds at every R since its λ left the local error test (issue 10, item 4); before, it
  // ran out of steps from R = 1e8 (100000 steps within one output interval).
  CHECK(record("stiffness", "R = 1e+08", Scheme::index1).status == "holds");
  CHECK(record("stiffness", "R = 1e+12", Scheme::index1).status == "holds");

  // Penalty: the error falls like 1/w (9.8e-3, 9.8e-5, 9.8e-7 observed for w = 1e2, 1e4, 1e6).
  const auto& w2 = record("penalty_weight", "w = 1e+02 max K_ii", Scheme::penalty);
  const auto& w4 = record("penalty_weight", "w = 1e+04 max K_ii", Scheme::penalty);
  const auto& w6 = record("penalty_weight", "w = 1e+06 max K_ii", Scheme::penalty);
  REQUIRE((w2.error && w4.error && w6.error));
  CHECK(*w2.error / *w4.error == doctest::Approx(100.0).epsilon(0.1));
  CHECK(*w4.error / *w6.error == doctest::Approx(100.0).epsilon(0.1));

  // Baumgarte on the pendulum: moderate gains hold, 1e4 x the natural frequency and beyond fail.
  CHECK(record("baumgarte_gains", "gains = 1e+02 omega", Scheme::baumgarte).status == "holds");
  for (const char* g : {"gains = 1e+04 omega", "gains = 1e+08 omega", "gains = 1e+12 omega"}) {
    CAPTURE(g);
    CHECK(record("baumgarte_gains", g, Scheme::baumgarte).status == "failed");
  }

  // Long horizons: GGL's drift stays bounded over 1e5 periods (observed 9.6e-11).
  CHECK(record("long_horizon", "1e+05 periods", Scheme::ggl).status == "holds");
  CHECK(record("long_horizon", "1e+05 periods", Scheme::projection).status == "holds");

  // Exactly redundant constraints: refused, both named; an angle of 1e-8 is accepted and GGL
  // holds, while penalty cannot enforce the nearly dependent direction.
  const auto& same = record("redundancy", "theta = 0", Scheme::ggl);
  CHECK(same.status == "refused");
  CHECK(same.reason.find("'second', 'first' are linearly dependent") != std::string::npos);
  CHECK(record("redundancy", "theta = 1e-08", Scheme::ggl).status == "holds");
  // The same pair with [solve] redundant = "drop": one row goes, and every scheme runs.
  CHECK(record("redundancy", "theta = 0, dropped", Scheme::ggl).status == "holds");
  CHECK(record("redundancy", "theta = 0, dropped", Scheme::elimination).status == "holds");
  CHECK(record("redundancy", "theta = 1e-08", Scheme::penalty).status == "inaccurate");

  // A massless DOF held by its springs (x3 between x2 and x4): an algebraic unknown that the
  // multiplier schemes, elimination and penalty integrate as a DAE and projection as an
  // index-reduced ODE with its row as an invariant, against the statically condensed exact
  // solution (penalty to its own accuracy, as on every chain).
  for (Scheme s : kSchemes) {
    const auto& r = record("mass_ratio", "m3 = 0", s);
    CAPTURE(std::string(to_string(s)));
    CAPTURE(r.reason);
    if (s == Scheme::penalty) {
      CHECK(r.status == record("mass_ratio", "r = 1e+00", s).status);
    } else {
      CHECK(r.status == "holds");
    }
  }

  // Near the four-bar's change point GGL holds where a reference exists (eps >= 1e-3).
  for (const char* eps : {"eps = 1e-01", "eps = 1e-02", "eps = 1e-03"}) {
    CAPTURE(eps);
    CHECK(record("dead_point", eps, Scheme::ggl).status == "holds");
  }

  // High-frequency loads: GGL holds at 1000 x the highest natural frequency, at more steps.
  const auto& slow = record("high_frequency", "omega = 1e+00 omega_max", Scheme::ggl);
  const auto& fast = record("high_frequency", "omega = 1e+03 omega_max", Scheme::ggl);
  CHECK(fast.status == "holds");
  CHECK(fast.steps > 10 * slow.steps);
}

TEST_CASE("stress: the output folder and the map") {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("condyn_stress_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  // A scene an earlier run of other families left, and a file of the user's: the first goes.
  fs::create_directories(dir / "scenes");
  { std::ofstream(dir / "scenes" / "stiffness_99.toml") << "# stale\n"; }
  { std::ofstream(dir / "scenes" / "mine.toml") << "# mine\n"; }
  write_stress_files(dir.string(), suite());
  CHECK_FALSE(fs::exists(dir / "scenes" / "stiffness_99.toml"));
  CHECK(fs::exists(dir / "scenes" / "mine.toml"));
  std::ifstream csv(dir / "stress.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(header ==
        "family,case,label,parameter,scheme,status,rtol,reference,error_u,max_drift_position,"
        "max_drift_velocity,energy_error,steps,wall_s,t_reached,reason,suggestion");
  std::stringstream all;
  all << csv.rdbuf();
  CHECK(all.str().find("nan") == std::string::npos);
  CHECK(all.str().find("inf,") == std::string::npos);
  CHECK(fs::exists(dir / "stress.json"));
  CHECK(fs::exists(dir / "summary.txt"));
  CHECK(fs::exists(dir / "scenes" / "redundancy_1.toml"));
  const std::string note = run_plot_script("plot_stress.py", dir.string());
  CAPTURE(note);
  CHECK(note.rfind("plots written", 0) == 0);
  CHECK(fs::file_size(dir / "stress_map.png") > 1000);
  fs::remove_all(dir);
}

}  // namespace test_stress_stress
