// What an output's name decides (docs/cli.md "Outputs", issue 42): the format its extension
// names or a refusal before any work, that `plot` reads what `run` writes under every name run
// accepts, the partial file's name (usable beside every legal output name), and that a finished
// run removes the partial file an earlier failure left under its name.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_output_names {

namespace fs = std::filesystem;
using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

const std::string& kScene = condyn::test::kTwoMassesScene;
const std::string kHeader = "t,a,b,drift_position,drift_velocity\n";
// Fails at t = 1 after ten output rows (tests/scene_text.hpp).
const std::string& kFailing = condyn::test::kPulledPendulumScene;

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// The HDF5 format signature, the first 8 bytes of a file without a user block (HDF5 spec,
/// "Format Signature").
bool is_hdf5(const fs::path& p) { return slurp(p).rfind("\x89HDF\r\n\x1a\n", 0) == 0; }

/// Files of `dir` whose names start with a dot: the temporary files of an output.
bool no_hidden_files(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().rfind('.', 0) == 0) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("run --out: the extension names the format, in any case, and no extension is CSV") {
  const Sandbox box;
  box.write("s.toml", kScene);
  for (const std::string name : {"r.h5", "r.hdf5", "r.hdf", "R.HDF", "r.H5"}) {
    CAPTURE(name);
    const Result r = box.run("run s.toml --out " + name);
    CAPTURE(r.err);
    REQUIRE(r.code == 0);
    CHECK(is_hdf5(box.path(name)));
  }
  for (const std::string name : {"r.csv", "r.CSV", "results"}) {
    CAPTURE(name);
    REQUIRE(box.run("run s.toml --out " + name).code == 0);
    CHECK(slurp(box.path(name)).rfind(kHeader, 0) == 0);
  }
  // [output] file follows the same rule.
  box.write("k.toml", kScene + "[output]\nfile = \"k.hdf\"\n");
  REQUIRE(box.run("run k.toml").code == 0);
  CHECK(is_hdf5(box.path("k.hdf")));
}

TEST_CASE("an output name whose extension names no format the option writes is refused") {
  const Sandbox box;
  box.write("s.toml", kScene);
  box.write("k.toml", kScene + "[output]\nfile = \"k.dat\"\n");
  box.write("c.toml", kScene + "[[check]]\nquantity = \"a\"\nmax_abs = 10.0\n");
  const auto file_line = std::count(kScene.begin(), kScene.end(), '\n') + 2;  // k.toml's file =
  struct Case {
    std::string args, said, written;
  };
  const std::vector<Case> cases = {
      {"run s.toml --out res.txt", "--out res.txt: the extension .txt names no format", "res.txt"},
      {"run s.toml --out res.hdf4", "--out res.hdf4: the extension .hdf4", "res.hdf4"},
      {"run s.toml --out res.", "--out res.: the extension .", "res."},
      {"run s.toml --out res.xml",
       "--out res.xml: the extension .xml asks for a format --out "
       "does not write",
       "res.xml"},
      {"run k.toml",
       "k.toml:" + std::to_string(file_line) + ": [output] file k.dat: the extension .dat",
       "k.dat"},
      {"run s.toml --out r.csv --steps-out d.h5", "--steps-out d.h5: the extension .h5 asks",
       "d.h5"},
      {"run s.toml --out r.csv --steps-out d.hdf", "--steps-out d.hdf:", "d.hdf"},
      {"run s.toml --out r.csv --steps-out d.txt", "--steps-out d.txt:", "d.txt"},
      {"check c.toml --junit report.csv", "--junit report.csv: the extension .csv asks",
       "report.csv"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.args);
    const Result r = box.run(c.args);
    CAPTURE(r.err);
    CHECK(r.code == 2);
    CHECK(contains(r.err, c.said));
    CHECK(!fs::exists(box.path(c.written)));
    CHECK(!fs::exists(box.path("r.csv")));  // refused before the run: nothing written
    CHECK(no_hidden_files(box.path(".")));
  }
  // The message names what the option accepts.
  const Result out = box.run("run s.toml --out res.txt");
  CHECK(contains(out.err,
                 "--out writes CSV (.csv, or a name without an extension) or HDF5 "
                 "(.h5, .hdf5, .hdf)"));
  const Result steps = box.run("run s.toml --steps-out d.h5");
  CHECK(contains(steps.err, "--steps-out writes CSV (.csv, or a name without an extension)"));
  // check's report: .xml, or no extension.
  const Result junit = box.run("check c.toml --junit report");
  CAPTURE(junit.err);
  CHECK(junit.code == 0);
  CHECK(slurp(box.path("report")).rfind("<?xml", 0) == 0);
}

TEST_CASE("condyn plot reads what run writes under every name run accepts") {
  const Sandbox box;
  box.write("s.toml", kScene);
  for (const std::string name : {"r.hdf", "q.HDF5", "plain"}) {
    CAPTURE(name);
    REQUIRE(box.run("run s.toml --scheme index1 --out " + name).code == 0);
    const Result plot = box.run("plot " + name + " --format svg");
    CAPTURE(plot.err);
    CHECK(plot.code == 0);
    const std::string stem = fs::path(name).stem().string();
    CHECK(fs::exists(box.path(stem + "_displacement.svg")));
  }
  // A name run refuses, plot refuses too, saying what it reads.
  box.write("r.txt", kHeader);
  const Result txt = box.run("plot r.txt");
  CHECK(txt.code == 2);
  CHECK(contains(txt.err, "r.txt: not a result file"));
  CHECK(contains(txt.err, "HDF5 (.h5, .hdf5, .hdf)"));
}

TEST_CASE("a legal output name of up to 255 bytes keeps a failed run's rows in a partial file") {
  const Sandbox box;
  box.write("p.toml", kFailing);
  // 255 bytes is the longest name Linux file systems take (NAME_MAX); NAME.partial.csv of a
  // 248-byte or longer name passes it, so those names were refused before the run.
  for (const std::size_t size : {247U, 248U, 249U, 255U}) {
    CAPTURE(size);
    const std::string name = std::string(size - 4, 'x') + ".csv";
    const Result r = box.run("run p.toml --out " + name);
    CAPTURE(r.err);
    CHECK(r.code == 1);  // the run failed at t = 1: not refused as bad input
    CHECK(!fs::exists(box.path(name)));
    std::vector<std::string> partials;
    for (const auto& entry : fs::directory_iterator(box.path("."))) {
      const std::string f = entry.path().filename().string();
      if (f.size() > 12 && f.substr(f.size() - 12) == ".partial.csv") partials.push_back(f);
    }
    REQUIRE(partials.size() == 1);
    CHECK(partials[0].size() <= 255);
    CHECK(contains(r.err, partials[0]));  // the message names it
    CHECK(slurp(box.path(partials[0])).rfind("t,", 0) == 0);
    fs::remove(box.path(partials[0]));
  }
  // Two long names that share their start get two partial files.
  const std::string stem(250, 'y');
  CHECK(box.run("run p.toml --out " + stem + "1.csv").code == 1);
  CHECK(box.run("run p.toml --out " + stem + "2.csv").code == 1);
  int partials = 0;
  for (const auto& entry : fs::directory_iterator(box.path("."))) {
    partials += entry.path().filename().string().find(".partial.csv") != std::string::npos;
  }
  CHECK(partials == 2);
  CHECK(no_hidden_files(box.path(".")));
}

TEST_CASE("a finished run removes the partial files an earlier failure left under its names") {
  const Sandbox box;
  box.write("s.toml", kScene);
  box.write("p.toml", kFailing);
  for (const std::string ext : {".csv", ".h5"}) {
    CAPTURE(ext);
    // A failure leaves out.partial.EXT (and the drift log's partial file) ...
    REQUIRE(box.run("run p.toml --out out" + ext + " --steps-out d.csv").code == 1);
    REQUIRE(fs::exists(box.path("out.partial" + ext)));
    REQUIRE(fs::exists(box.path("d.partial.csv")));
    // ... which a later success under the same names removes, and says so.
    const Result ok = box.run("run s.toml --out out" + ext + " --steps-out d.csv");
    CAPTURE(ok.err);
    REQUIRE(ok.code == 0);
    CHECK(fs::exists(box.path("out" + ext)));
    CHECK(!fs::exists(box.path("out.partial" + ext)));
    CHECK(!fs::exists(box.path("d.partial.csv")));
    CHECK(contains(ok.out, "removed out.partial" + ext));
  }
  // Only its own names': another output's partial file stays.
  box.write("other.partial.csv", "kept\n");
  REQUIRE(box.run("run s.toml --out out.csv").code == 0);
  CHECK(slurp(box.path("other.partial.csv")) == "kept\n");
}

}  // namespace test_cli_output_names
