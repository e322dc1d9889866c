// Output safety (docs/cli.md "Outputs"): every output of a command is checked before any work, none
// may be an input or another output, all are committed together, streams (standard output,
// devices, FIFOs) are written in place, temporary files never outlive the process.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_output {

namespace fs = std::filesystem;
using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

const std::string& kScene = condyn::test::kTwoMassesScene;
const std::string kHeader = "t,a,b,drift_position,drift_velocity\n";

// A run that fails at t = 1 (test_cli.cpp explains why): an output checked only after the
// integration shows up as exit 1 there, one checked before it as exit 2 with no solver message.
const std::string& kFailing = condyn::test::kPulledPendulumScene;

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// Files of `dir` whose names start with a dot: the temporary files of an output.
std::vector<std::string> hidden_files(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind('.', 0) == 0) out.push_back(name);
  }
  return out;
}

/// Every line of `csv` after the header has as many fields as the header and only numbers.
bool pure_csv(const std::string& csv, const std::string& header) {
  if (csv.rfind(header, 0) != 0) return false;
  const auto fields = std::count(header.begin(), header.end(), ',') + 1;
  std::istringstream lines(csv.substr(header.size()));
  int rows = 0;
  for (std::string line; std::getline(lines, line); ++rows) {
    if (std::count(line.begin(), line.end(), ',') + 1 != fields) return false;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) {
      std::size_t used = 0;
      try {
        (void)std::stod(cell, &used);
      } catch (const std::exception&) {
        return false;
      }
      if (used != cell.size()) return false;
    }
  }
  return rows > 0;
}

}  // namespace

TEST_CASE("no output may be an input: the scene is never overwritten") {
  const Sandbox box;
  box.write("s.toml", kScene);
  const auto unchanged = [&]() { return slurp(box.path("s.toml")) == kScene; };

  const Result flag = box.run("run s.toml --out s.toml");
  CHECK(flag.code == 2);
  CHECK(contains(flag.err, "--out s.toml: is s.toml, an input of this command"));
  CHECK(unchanged());

  // [output] file naming the scene, by the same name or another one (a link, a hard link).
  box.write("o.toml", kScene + "[output]\nfile = \"o.toml\"\n");
  const Result key = box.run("run o.toml");
  CHECK(key.code == 2);
  // At the key's line (the scene's last).
  const auto file_line = std::count(kScene.begin(), kScene.end(), '\n') + 2;
  CHECK(contains(key.err, "o.toml:" + std::to_string(file_line) +
                              ": [output] file o.toml: is o.toml, an input"));
  CHECK(slurp(box.path("o.toml")) == kScene + "[output]\nfile = \"o.toml\"\n");
  fs::create_symlink("s.toml", box.path("link.csv"));
  CHECK(box.run("run s.toml --out link.csv").code == 2);
  fs::create_hard_link(box.path("s.toml"), box.path("hard.csv"));
  CHECK(box.run("run s.toml --out hard.csv").code == 2);
  CHECK(box.run("run s.toml --steps-out ./s.toml --out r.csv").code == 2);
  CHECK(unchanged());
  CHECK(!fs::exists(box.path("r.csv")));

  // The default output (SCENE-STEM.csv) of a scene whose name ends in .csv is the scene.
  box.write("x.csv", kScene);
  CHECK(box.run("run x.csv").code == 2);
  CHECK(slurp(box.path("x.csv")) == kScene);

  // The file a failed run would keep its rows in is an output too.
  box.write("p.partial.csv", kFailing);
  const Result partial = box.run("run p.partial.csv --out p.csv");
  CHECK(partial.code == 2);
  CHECK(contains(partial.err, "p.partial.csv: is p.partial.csv, an input"));
  CHECK(slurp(box.path("p.partial.csv")) == kFailing);
  CHECK(hidden_files(box.path(".")).empty());
}

TEST_CASE("no output may be a file the scene names: its matrices, tables and references") {
  const Sandbox box;
  const std::string k =
      "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 3\n2 1 -1\n2 2 1\n";
  const std::string record = "t,a\n0,0\n1,1\n";
  box.write("K.mtx", k);
  box.write("record.csv", record);
  std::string scene = kScene;
  scene.replace(scene.find("stiffness = [[3.0, -1.0], [-1.0, 1.0]]"),
                std::string("stiffness = [[3.0, -1.0], [-1.0, 1.0]]").size(),
                "stiffness = { file = \"K.mtx\" }");
  scene.replace(scene.find("value = { type = \"step\""), std::string::npos,
                "value = { type = \"table\", file = \"record.csv\" }\n"
                "[[constraint]]\nname = \"tie\"\nterms = { a = 1.0 }\n"
                "[solve]\nt_end = 1.0\noutput_step = 0.25\n");
  box.write("m.toml", scene);
  REQUIRE(box.run("run m.toml --out ok.csv").code == 0);
  for (const std::string input : {"K.mtx", "record.csv", "./K.mtx"}) {
    CAPTURE(input);
    const Result r = box.run("run m.toml --out " + input);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "an input of this command"));
  }
  CHECK(box.run("run m.toml --out ok.csv --steps-out record.csv").code == 2);
  CHECK(slurp(box.path("K.mtx")) == k);
  CHECK(slurp(box.path("record.csv")) == record);
}

TEST_CASE(
    "compare and stress: their files never overwrite or remove an input or a protected file") {
  const Sandbox box;
  const std::string record = "t,a\n0,0\n1,1\n";
  std::string scene = kScene;
  scene.replace(scene.find("value = { type = \"step\""), std::string::npos,
                "value = { type = \"table\", file = \"TABLE\" }\n"
                "[solve]\nt_end = 1.0\noutput_step = 0.25\n");
  auto with_table = [&](const std::string& name) {
    std::string s = scene;
    s.replace(s.find("TABLE"), 5, name);
    return s;
  };
  const std::string compare = "--no-plots --repeats 1 --tolerances 1e-4 --schemes ggl --out-dir .";
  // A table named as a file compare writes: refused before any run, the table intact.
  box.write("runs.csv", record);
  box.write("a.toml", with_table("runs.csv"));
  const Result written = box.run("compare a.toml " + compare);
  CHECK(written.code == 2);
  CHECK(contains(written.err, "an input of this command"));
  CHECK(slurp(box.path("runs.csv")) == record);
  // A table named as a file a comparison of other schemes would have left: not removed.
  box.write("drift_index1.csv", record);
  box.write("b.toml", with_table("drift_index1.csv"));
  // A read-only figure of an earlier comparison: protected, kept.
  box.write("drift.png", "not a figure\n");
  fs::permissions(box.path("drift.png"), fs::perms::owner_read);
  // A writable stale file goes (history_index2.csv, from a comparison with index2).
  box.write("history_index2.csv", "stale\n");
  // And the log of figures this run does not draw (--no-plots).
  box.write("plots.log", "plot_compare: wrote drift.png\n");
  const Result ok = box.run("compare b.toml " + compare);
  CHECK(ok.code == 0);
  CHECK(!fs::exists(box.path("plots.log")));
  CHECK(slurp(box.path("drift_index1.csv")) == record);
  CHECK(fs::exists(box.path("drift.png")));
  CHECK(!fs::exists(box.path("history_index2.csv")));
  // stress keeps a read-only scene of another family in scenes/ and removes a writable one.
  fs::create_directories(box.path("st/scenes"));
  box.write("st/scenes/stiffness_1.toml", "kept\n");
  fs::permissions(box.path("st/scenes/stiffness_1.toml"), fs::perms::owner_read);
  box.write("st/scenes/stiffness_2.toml", "stale\n");
  CHECK(box.run("stress --no-plots --families dead_point --out-dir st").code == 0);
  CHECK(slurp(box.path("st/scenes/stiffness_1.toml")) == "kept\n");
  CHECK(!fs::exists(box.path("st/scenes/stiffness_2.toml")));
}

TEST_CASE("[output] file is relative to the scene's folder, --out is relative to here") {
  const Sandbox box;
  fs::create_directory(box.path("sub"));
  box.write("sub/s.toml", kScene + "[output]\nfile = \"r.csv\"\n");
  const Result r = box.run("run sub/s.toml");
  CHECK(r.code == 0);
  CHECK(fs::exists(box.path("sub/r.csv")));
  CHECK(!fs::exists(box.path("r.csv")));
  CHECK(contains(r.out, "sub/r.csv"));
  CHECK(box.run("run sub/s.toml --out here.csv").code == 0);
  CHECK(fs::exists(box.path("here.csv")));
}

TEST_CASE("an HDF5 result: .h5 in any case, or .hdf5") {
  const Sandbox box;
  box.write("s.toml", kScene);
  for (const std::string name : {"r.H5", "r.hdf5", "r.h5"}) {
    CAPTURE(name);
    CHECK(box.run("run s.toml --out " + name).code == 0);
    CHECK(slurp(box.path(name)).substr(0, 4) == "\x89HDF");  // HDF5's signature
  }
}

TEST_CASE("bad names: an empty --out, a folder for the scene") {
  const Sandbox box;
  box.write("s.toml", kScene);
  const Result empty = box.run("run s.toml --out ''");
  CHECK(empty.code == 2);
  CHECK(contains(empty.err, "--out: an empty name"));
  CHECK(box.run("run s.toml --steps-out ''").code == 2);
  CHECK(!fs::exists(box.path("s.csv")));
  fs::create_directory(box.path("d"));
  for (const std::string command : {"run d", "info d", "check d"}) {
    CAPTURE(command);
    const Result r = box.run(command);
    CHECK(r.code == 2);
    CHECK(contains(r.err + r.out, "d: is a folder (name a scene file)"));
  }
}

TEST_CASE("--out and --steps-out: checked together before the run, committed together") {
  const Sandbox box;
  box.write("f.toml", kFailing);
  box.write("keep.csv", "precious\n");

  // The same file twice: refused, before the integration (exit 2, not the solver's exit 1).
  const Result same = box.run("run f.toml --steps-out keep.csv --out keep.csv");
  CHECK(same.code == 2);
  CHECK(contains(same.err, "--steps-out keep.csv: is the same file as --out keep.csv"));
  CHECK(!contains(same.err, "integration failed"));
  CHECK(slurp(box.path("keep.csv")) == "precious\n");

  // A --steps-out that cannot be written: refused before --out is touched.
  const Result bad = box.run("run f.toml --out keep.csv --steps-out missing/steps.csv");
  CHECK(bad.code == 2);
  CHECK(contains(bad.err, "--steps-out missing/steps.csv: the folder"));
  CHECK(contains(bad.err, "missing does not exist"));
  CHECK(!contains(bad.err, "integration failed"));
  CHECK(slurp(box.path("keep.csv")) == "precious\n");

  // --steps-out naming where a failed run keeps --out's rows.
  CHECK(box.run("run f.toml --out keep.csv --steps-out keep.partial.csv").code == 2);
  CHECK(!fs::exists(box.path("keep.partial.csv")));

  // A good pair: both written.
  box.write("s.toml", kScene);
  const Result ok = box.run("run s.toml --out keep.csv --steps-out steps.csv --scheme ggl");
  CAPTURE(ok.err);
  CHECK(ok.code == 0);
  CHECK(slurp(box.path("keep.csv")).rfind(kHeader, 0) == 0);
  CHECK(slurp(box.path("steps.csv")).rfind("t,drift_position,drift_velocity\n", 0) == 0);
  CHECK(hidden_files(box.path(".")).empty());

  // A failed run keeps its drift log too, beside the partial rows: the steps before the failure
  // are what tells why it failed. steps.csv keeps what it had.
  const std::string finished = slurp(box.path("steps.csv"));
  const Result failed = box.run("run f.toml --out keep.csv --steps-out steps.csv");
  CHECK(failed.code == 1);
  CHECK(contains(failed.err, "are in keep.partial.csv"));
  CHECK(contains(failed.err, "internal steps is in steps.partial.csv"));
  CHECK(slurp(box.path("steps.partial.csv")).rfind("t,drift_position,drift_velocity\n1", 0) == 0);
  CHECK(slurp(box.path("steps.csv")) == finished);
  CHECK(hidden_files(box.path(".")).empty());
  // The drift log is CSV: a .h5 name is refused before the run.
  const Result h5 = box.run("run s.toml --out o.csv --steps-out steps.h5");
  CHECK(h5.code == 2);
  CHECK(contains(h5.err,
                 "--steps-out steps.h5: the extension .h5 asks for a format --steps-out "
                 "does not write: --steps-out writes CSV"));
  // Its partial name is checked before the run as well.
  const Result clash = box.run("run f.toml --out steps.partial.csv --steps-out steps.csv");
  CHECK(clash.code == 2);
  CHECK(!contains(clash.err, "integration failed"));
}

TEST_CASE("a path that cannot be written is refused before any work") {
  const Sandbox box;
  box.write("f.toml", kFailing);
  box.write("afile", "not a folder\n");
  const Result missing = box.run("run f.toml --out nowhere/x.csv");
  CHECK(missing.code == 2);
  CHECK(contains(missing.err, "--out nowhere/x.csv: the folder"));
  CHECK(!contains(missing.err, "integration failed"));
  const Result under_file = box.run("run f.toml --out afile/x.csv");
  CHECK(under_file.code == 2);
  CHECK(contains(under_file.err, "afile is not a folder"));
  const Result folder = box.run("run f.toml --out .");
  CHECK(folder.code == 2);
  CHECK(contains(folder.err, "is a folder"));
  // A name longer than the file system takes: the temporary file beside it (a short name) was
  // created, the run done, and the rename failed after --out had replaced its file (exit 1).
  box.write("kept.csv", "the user's\n");
  const std::string long_name(256, 'c');
  for (const std::string& cmd : {"run f.toml --out " + long_name + ".csv",
                                 "run f.toml --out kept.csv --steps-out " + long_name + ".csv",
                                 "run f.toml --out nowhere/" + long_name + ".csv"}) {
    CAPTURE(cmd);
    const Result r = box.run(cmd);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "File name too long (at most 255 bytes a name)"));
    CHECK(!contains(r.err, "integration failed"));
  }
  CHECK(slurp(box.path("kept.csv")) == "the user's\n");

  // compare and stress: the folder is checked before the first run (no progress line).
  for (const std::string& cmd :
       {std::string("compare --no-plots --repeats 1 --tolerances 1e-4 --out-dir afile"),
        std::string("compare --no-plots --repeats 1 --tolerances 1e-4 --out-dir afile/sub"),
        std::string("stress --no-plots --families stiffness --out-dir afile"),
        std::string("stress --no-plots --out-dir afile"),  // every family, the default
        std::string("compare --no-plots --repeats 1 --tolerances 1e-4 --out-dir /dev/null/x")}) {
    CAPTURE(cmd);
    const Result r = box.run(cmd);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--out-dir"));
    CHECK(contains(r.err, "not a folder"));
    CHECK(!contains(r.err, "[1/"));  // progress lines start "[k/n]"
  }
  CHECK(slurp(box.path("afile")) == "not a folder\n");

  // A compare scene inside its --out-dir under one of the file names compare writes.
  fs::create_directory(box.path("out"));
  const std::string truss =
      slurp(fs::path(CONDYN_SOURCE_DIR) / "validation/scenes" / "chapter_5_5_1.toml");
  REQUIRE(!truss.empty());
  box.write("out/summary.txt", truss);
  const Result input =
      box.run("compare out/summary.txt --no-plots --repeats 1 --tolerances 1e-4 --out-dir out");
  CHECK(input.code == 2);
  CHECK(contains(input.err, "an input of this command"));
  CHECK(slurp(box.path("out/summary.txt")) == truss);
}

TEST_CASE("a failed run writes no .partial beside a device, FIFO or standard output") {
  const Sandbox box;
  box.write("f.toml", kFailing);
  const Result null = box.run("run f.toml --out /dev/null");
  CHECK(null.code == 1);
  CHECK(contains(null.err, "partial result: the 10 output rows up to t = 0.9 were not written"));
  CHECK(contains(null.err, "give --out FILE to keep them"));
  struct stat st {};
  REQUIRE(::stat("/dev/null", &st) == 0);
  CHECK(S_ISCHR(st.st_mode));

  REQUIRE(::mkfifo(box.path("pipe.csv").c_str(), 0600) == 0);
  const Result fifo = box.run("run f.toml --out pipe.csv");  // nothing opens the FIFO: no reader
  CHECK(fifo.code == 1);
  CHECK(contains(fifo.err, "were not written"));
  CHECK(fs::is_fifo(fs::symlink_status(box.path("pipe.csv"))));
  CHECK(!fs::exists(box.path("pipe.partial.csv")));

  const Result out = box.run("run f.toml --out -");
  CHECK(out.code == 1);
  CHECK(out.out.empty());
  CHECK(contains(out.err, "were not written (standard output is not a file"));
  CHECK(!fs::exists(box.path("-")));
  CHECK(!fs::exists(box.path("-.partial")));
  CHECK(box.run("run f.toml --out /dev/stdout").out.empty());
  CHECK(hidden_files(box.path(".")).empty());
}

TEST_CASE("CSV on standard output: stdout is the CSV alone, every other line on stderr") {
  const Sandbox box;
  box.write("s.toml", kScene);
  for (const char* target : {"-", "/dev/stdout"}) {
    CAPTURE(target);
    const Result r = box.run(std::string("run s.toml --out ") + target);
    CHECK(r.code == 0);
    CHECK(pure_csv(r.out, kHeader));
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1 + 5);  // t = 0, 0.25, ..., 1
    CHECK(contains(r.err, "elimination: reached t = 1"));
    CHECK(contains(r.err, "wrote 5 rows to "));
  }
  CHECK(!fs::exists(box.path("-")));
  const Result steps = box.run("run s.toml --out r.csv --steps-out - --scheme ggl");
  CHECK(steps.code == 0);
  CHECK(pure_csv(steps.out, "t,drift_position,drift_velocity\n"));
  CHECK(contains(steps.err, "internal steps to standard output"));
  CHECK(slurp(box.path("r.csv")).rfind(kHeader, 0) == 0);
  const Result both = box.run("run s.toml --out - --steps-out /dev/stdout");
  CHECK(both.code == 2);
  CHECK(contains(both.err, "standard output already takes --out"));
  CHECK(both.out.empty());
  // Standard output redirected to a file (the sandbox's out.txt) that another output names.
  const Result redirected = box.run("run s.toml --out - --steps-out out.txt");
  CHECK(redirected.code == 2);
  CHECK(contains(redirected.err, "--steps-out out.txt: is the same file as --out -"));
}

TEST_CASE("SIGTERM or SIGINT while the CSV is written keeps the rows, leaves no temporary file") {
  const Sandbox box;
  // 40 oscillators started at 1, 50001 output rows: a CSV of about 40 MB, long enough to write
  // that the signal lands during the write.
  const int n = 40;
  std::ostringstream s;
  s << "[model]\ntype = \"matrix\"\ndofs = [";
  for (int i = 0; i < n; ++i) s << (i ? ", " : "") << "\"x" << i << "\"";
  s << "]\n";
  for (const char* key : {"mass", "stiffness"}) {
    s << key << " = [";
    for (int i = 0; i < n; ++i) {
      s << (i ? ", " : "") << "[";
      for (int j = 0; j < n; ++j) s << (j ? ", " : "") << (i == j ? 1.0 + 0.01 * i : 0.0);
      s << "]";
    }
    s << "]\n";
  }
  s << "[initial]\ndisplacement = {";
  for (int i = 0; i < n; ++i) s << (i ? ", " : " ") << "x" << i << " = 1.0";
  s << " }\n[solve]\nt_end = 1000.0\noutput_step = 0.02\nrtol = 1e-4\natol = 1e-6\n";
  box.write("big.toml", s.str());
  std::string header = "t";
  for (int i = 0; i < n; ++i) header += ",x" + std::to_string(i);
  header += ",drift_position,drift_velocity\n";

  for (const int signal : {SIGTERM, SIGINT}) {
    CAPTURE(signal);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      if (::chdir(box.path(".").c_str()) != 0) ::_exit(126);
      const int null = ::open("/dev/null", O_WRONLY);
      const int err = ::open("err.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(null, 1);
      ::dup2(err, 2);
      ::execl(CONDYN_BINARY, "condyn", "run", "big.toml", "--out", "big.csv", nullptr);
      ::_exit(127);
    }
    // Wait until a temporary file holds data: the CSV is being written.
    bool writing = false;
    int status = 0;
    bool exited = false;
    for (int k = 0; k < 120000 && !writing && !exited; ++k) {
      for (const auto& name : hidden_files(box.path("."))) {
        std::error_code ec;
        writing = writing || fs::file_size(box.path(name), ec) > 0;
      }
      exited = ::waitpid(pid, &status, WNOHANG) == pid;
      if (!writing && !exited) ::usleep(500);
    }
    if (!exited) {
      ::kill(pid, signal);
      REQUIRE(::waitpid(pid, &status, 0) == pid);
    }
    REQUIRE(writing);
    // The process ends by the signal, as before, so a shell sees 128 + N (130, 143) ...
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == signal);
    CHECK(hidden_files(box.path(".")).empty());
    CHECK(!fs::exists(box.path("big.csv")));
    // ... after keeping the rows computed, as a failed run does: complete rows from t = 0 on.
    const std::string partial = slurp(box.path("big.partial.csv"));
    CHECK(pure_csv(partial, header));
    CHECK(partial.rfind(header + "0,", 0) == 0);
    CHECK(!partial.empty());
    CHECK(partial.back() == '\n');
    const std::string err = slurp(box.path("err.txt"));
    CAPTURE(err);
    CHECK(contains(err, "run stopped: under "));
    CHECK(contains(err, signal == SIGINT ? "stopped by SIGINT (Ctrl-C) at t = "
                                         : "stopped by SIGTERM at t = "));
    CHECK(contains(
        err, " are in big.partial.csv (the run did not reach t_end; big.csv was not written)"));
    fs::remove(box.path("big.partial.csv"));
  }
}

TEST_CASE("links and permissions: what replacing an output keeps") {
  const Sandbox box;
  box.write("s.toml", kScene);

  // A dangling link: the file it names is created, the link stays a link.
  fs::create_symlink("target.csv", box.path("dangling.csv"));
  const Result dangling = box.run("run s.toml --out dangling.csv");
  CHECK(dangling.code == 0);
  CHECK(fs::is_symlink(fs::symlink_status(box.path("dangling.csv"))));
  CHECK(slurp(box.path("target.csv")).rfind(kHeader, 0) == 0);
  // A link into a folder that does not exist: refused before the run.
  fs::create_symlink("nowhere/x.csv", box.path("lost.csv"));
  const Result lost = box.run("run s.toml --out lost.csv");
  CHECK(lost.code == 2);
  CHECK(contains(lost.err, "nowhere does not exist"));

  // An existing file keeps its permission bits.
  box.write("mode.csv", "old\n");
  fs::permissions(box.path("mode.csv"),
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  CHECK(box.run("run s.toml --out mode.csv").code == 0);
  CHECK(fs::status(box.path("mode.csv")).permissions() ==
        (fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read));
  CHECK(slurp(box.path("mode.csv")).rfind(kHeader, 0) == 0);

  // A file without any write permission is protected: refused, untouched.
  box.write("ro.csv", "protected\n");
  fs::permissions(box.path("ro.csv"), fs::perms::owner_read | fs::perms::group_read);
  const Result ro = box.run("run s.toml --out ro.csv");
  CHECK(ro.code == 2);
  CHECK(contains(ro.err, "--out ro.csv: is read-only"));
  CHECK(slurp(box.path("ro.csv")) == "protected\n");

  // A file with other hard links is replaced (atomically); its other names keep the previous
  // content, and the run says so.
  box.write("linked.csv", "old\n");
  fs::create_hard_link(box.path("linked.csv"), box.path("other.csv"));
  const Result hard = box.run("run s.toml --out linked.csv");
  CHECK(hard.code == 0);
  CHECK(contains(hard.err, "linked.csv had 2 hard links"));
  CHECK(slurp(box.path("linked.csv")).rfind(kHeader, 0) == 0);
  CHECK(slurp(box.path("other.csv")) == "old\n");
  CHECK(hidden_files(box.path(".")).empty());
}

}  // namespace test_cli_output
