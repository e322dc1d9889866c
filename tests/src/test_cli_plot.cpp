// `condyn plot RESULT` (issue 14, docs/plots.md): figures of one run's CSV or HDF5, and clear
// refusals (exit 2, the file or DOF named) of what it cannot draw.
#include <doctest/doctest.h>

#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_plot {

using condyn::test::Result;
using condyn::test::Sandbox;

namespace {

/// The two-mass scene with displacement, drift and the energy balance written.
void write_run(const Sandbox& box) {
  box.write("s.toml", condyn::test::replace(condyn::test::kTwoMassesScene, "output_step = 0.25\n",
                                            "output_step = 0.05\n[output]\nquantities = "
                                            "[\"displacement\", \"drift\", \"energy\"]\n"));
}

/// A PNG (its 8-byte signature) or PDF ("%PDF") file of some size.
bool is_figure(const Sandbox& box, const std::string& name) {
  const auto path = box.path(name);
  if (!std::filesystem::exists(path) || std::filesystem::file_size(path) < 5000) return false;
  const std::string head = condyn::test::slurp(path).substr(0, 4);
  return head == "\x89PNG" || head == "%PDF";
}

}  // namespace

TEST_CASE("condyn plot draws displacements, drift and energy of a CSV and of an HDF5 result") {
  const Sandbox box;
  write_run(box);
  // index1 lets the constraint drift, so the drift figure has something to show
  REQUIRE(box.run("run s.toml --scheme index1 --out r.csv").code == 0);
  REQUIRE(box.run("run s.toml --scheme index1 --out r.h5").code == 0);
  const Result csv = box.run("plot r.csv");
  CAPTURE(csv.err);
  REQUIRE(csv.code == 0);
  for (const char* what : {"displacement", "drift", "energy"}) {
    CAPTURE(what);
    CHECK(is_figure(box, std::string("r_") + what + ".png"));
    CHECK(is_figure(box, std::string("r_") + what + ".pdf"));
  }
  const Result h5 = box.run("plot r.h5 --dofs b --format svg --out-dir figs");
  CAPTURE(h5.err);
  REQUIRE(h5.code == 0);
  CHECK(h5.out.find("figs/r_displacement.svg") != std::string::npos);
  CHECK(std::filesystem::exists(box.path("figs/r_energy.svg")));
  CHECK_FALSE(std::filesystem::exists(box.path("figs/r_energy.png")));
}

TEST_CASE("condyn plot: DOFs named energy_* or work_* are displacements, not energy terms") {
  const Sandbox box;
  std::string scene = condyn::test::kTwoMassesScene;
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"\"a\", \"b\"", "\"energy_top\", \"work_1\""},
        {"dof = \"b\"", "dof = \"work_1\""},
        {"terms = { a = 1.0 }", "terms = { energy_top = 1.0 }"}}) {
    scene = condyn::test::replace(scene, from, to);
  }
  box.write("e.toml", scene);
  REQUIRE(box.run("run e.toml --scheme ggl --out e.csv").code == 0);
  REQUIRE(box.run("run e.toml --scheme ggl --out e.h5").code == 0);
  for (const char* result : {"e.csv", "e.h5"}) {
    CAPTURE(result);
    const Result r = box.run(std::string("plot ") + result + " --format png --dofs work_1");
    CAPTURE(r.err);
    REQUIRE(r.code == 0);
    CHECK(is_figure(box, "e_displacement.png"));
    CHECK_FALSE(std::filesystem::exists(box.path("e_energy.png")));  // no energy written
    std::filesystem::remove(box.path("e_displacement.png"));
  }
}

TEST_CASE("condyn plot draws no drift figure when the drift is exactly 0, and says so") {
  const Sandbox box;
  write_run(box);
  REQUIRE(box.run("run s.toml --scheme elimination --out e.csv").code == 0);
  const Result r = box.run("plot e.csv --format png");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("note: e: drift exactly 0 at every output time") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(box.path("e_drift.png")));
  CHECK(is_figure(box, "e_displacement.png"));
  CHECK(is_figure(box, "e_energy.png"));
}

TEST_CASE("condyn plot refuses what it cannot draw, naming the file or the DOF") {
  const Sandbox box;
  write_run(box);
  REQUIRE(box.run("run s.toml --out r.csv").code == 0);
  const auto refused = [&](const std::string& args, const std::string& expected) {
    const Result r = box.run(args);
    CAPTURE(args);
    CAPTURE(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.find(expected) != std::string::npos);
  };
  refused("plot missing.csv", "missing.csv: no such file");
  refused("plot s.toml", "s.toml: not a result file");
  box.write("other.csv", "a,b\n1,2\n");
  refused("plot other.csv", "other.csv: not a condyn result (its first column is not t)");
  box.write("torn.csv", "t,a\n0,1\n1\n");
  refused("plot torn.csv", "torn.csv:3: 1 cells for the header's 2 columns");
  box.write("word.csv", "t,a\n0,1\n1,x\n");
  refused("plot word.csv", "word.csv:3: 'x' is not a number");
  box.write("header.csv", "t,a\n");
  refused("plot header.csv", "header.csv: no rows");
  std::filesystem::create_directories(box.path("dir.csv"));
  refused("plot dir.csv", "dir.csv: is a folder");
  // A FIFO is no file to read (it would block): named as what it is, not as missing.
  REQUIRE(::mkfifo(box.path("fifo.csv").c_str(), 0600) == 0);
  refused("plot fifo.csv", "fifo.csv: not a regular file");
  box.write("fake.h5", "not hdf5");
  refused("plot fake.h5", "fake.h5: not an HDF5 file");
  refused("plot r.csv --dofs zz", "--dofs: 'zz' matches no DOF of r.csv (DOFs: a, b)");
  // Only * is a wildcard, as in [output] dofs: ? is a character of a name.
  refused("plot r.csv --dofs '?'", "--dofs: '?' matches no DOF of r.csv");
  refused("plot r.csv --format gif", "--format: unknown format 'gif'");
  refused("plot r.csv --format ''", "--format: is empty");
  // The list rules of every list flag: no stray comma, nothing twice.
  refused("plot r.csv --format png,", "--format: an empty item in 'png,'");
  refused("plot r.csv --format png,png", "--format: 'png' is listed twice");
  // A folder made for the figures goes again when nothing is drawn.
  refused("plot r.csv --out-dir new/inner --dofs zz", "--dofs: 'zz' matches no DOF");
  CHECK_FALSE(std::filesystem::exists(box.path("new")));
  // The figures are checked before any is drawn, as run's files are: a folder in the way, a
  // protected (read-only) file.
  std::filesystem::create_directories(box.path("r_energy.pdf"));
  refused("plot r.csv", "the figure r_energy.pdf: is a folder");
  CHECK_FALSE(std::filesystem::exists(box.path("r_displacement.png")));
  std::filesystem::remove(box.path("r_energy.pdf"));
  box.write("r_drift.png", "old");
  std::filesystem::permissions(box.path("r_drift.png"), std::filesystem::perms::owner_read |
                                                            std::filesystem::perms::group_read |
                                                            std::filesystem::perms::others_read);
  refused("plot r.csv", "the figure r_drift.png: is read-only");
  CHECK(condyn::test::slurp(box.path("r_drift.png")) == "old");
}

TEST_CASE("condyn plot draws names as written, many DOFs without a legend, and refuses 1e308") {
  const Sandbox box;
  // $ is legal in a DOF name and in a file name; matplotlib read 'x$\foo$' as math and the
  // script ended in a traceback (exit 1).
  box.write("m.csv", "t,x$\\foo$,y$_1$\n0,0.1,0\n0.5,0.05,0.02\n1,0,0.04\n");
  const Result math = box.run("plot m.csv --format png");
  CAPTURE(math.err);
  CHECK(math.code == 0);
  CHECK(is_figure(box, "m_displacement.png"));
  // 30 DOFs: drawn, without the legend that would outgrow the figure, and said so.
  std::string wide = "t";
  for (int i = 1; i <= 30; ++i) wide += ",u" + std::to_string(i);
  for (int k = 0; k < 3; ++k) {
    wide += "\n" + std::to_string(k);
    for (int i = 1; i <= 30; ++i) wide += "," + std::to_string(i * k);
  }
  box.write("w.csv", wide + "\n");
  const Result many = box.run("plot w.csv --format png --dofs 'u*'");
  CHECK(many.code == 0);
  CHECK(many.out.find("30 DOFs drawn without a legend (more than 12)") != std::string::npos);
  // Values near the double range broke matplotlib's ticks (a traceback): refused by name.
  box.write("h.csv", "t,x,y\n0,1e308,-1e308\n1,1.7e308,0\n");
  const Result huge = box.run("plot h.csv --format png");
  CHECK(huge.code == 2);
  CHECK(huge.err.find("h.csv: column x: values up to 1.7e+308 are too near the double range") !=
        std::string::npos);
  // A drift of NaN is no 'drift exactly 0': condyn writes no NaN (a NaN in the state stops the
  // run), so the file is refused, the cell named (issue 42).
  box.write("n.csv", "t,x,drift_position,drift_velocity\n0,1,nan,nan\n1,2,nan,nan\n");
  const Result nan = box.run("plot n.csv --format png");
  CHECK(nan.code == 2);
  CHECK(nan.err.find("n.csv:2: column drift_position: 'nan' is not a finite number") !=
        std::string::npos);
  CHECK(nan.out.find("exactly 0") == std::string::npos);
  // Nothing but a drift of exactly 0: the note says why, the refusal does not deny the columns.
  box.write("z.csv", "t,drift_position,drift_velocity\n0,0,0\n1,0,0\n");
  const Result zero = box.run("plot z.csv --format png");
  CHECK(zero.code == 2);
  CHECK(zero.out.find("note: z: drift exactly 0 at every output time") != std::string::npos);
  CHECK(zero.err.find("z.csv: nothing to draw (the notes above say why)") != std::string::npos);
}

}  // namespace test_cli_plot
