// `condyn check` (scene-format.md, "Checks for a user's own validation suite") and compare's exit
// codes and budgets (issue 14): what a CI job sees.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_check {

using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

/// A unit oscillator released from u = 1 (u = cos t exactly) with the checks given.
std::string scene(const std::string& checks) {
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
rtol = 1e-10
atol = 1e-12
)" + checks;
}

// cos(1) = 0.5403023058681398.
const std::string kHolds =
    "[[check]]\nquantity = \"x\"\nat = 1.0\nvalue = 0.5403023058681398\ntolerance = 1e-7\n";
const std::string kFails = "[[check]]\nquantity = \"x\"\nat = 1.0\nvalue = 0.5\ntolerance = 1e-3\n";

/// Counts in the JUnit report, read by Python's XML parser (as a CI system would read it).
std::string junit_counts(const Sandbox& box, const std::string& file) {
  box.write("count.py",
            "import sys, xml.etree.ElementTree as E\n"
            "r = E.parse(sys.argv[1]).getroot()\n"
            "print(r.tag, r.get('tests'), r.get('failures'), r.get('errors'),\n"
            "      len(r.findall('testsuite')), len(r.findall('.//failure')))\n");
  const std::string cmd = "cd '" + box.path("").string() + "' && /usr/bin/python3 count.py " +
                          file + " > counts.txt 2>&1";
  (void)std::system(cmd.c_str());
  return slurp(box.path("counts.txt"));
}

}  // namespace

TEST_CASE("cli check: every check holds: exit 0, one line per check, a JUnit report") {
  Sandbox box;
  box.write("a.toml", scene(kHolds));
  box.write("b.toml", scene("[[check]]\nquantity = \"vel_x\"\nmax_abs = 1.0000001\n"));
  const Result r = box.run("check a.toml b.toml --junit report.xml");
  CAPTURE(r.out);
  CAPTURE(r.err);
  CHECK(r.code == 0);
  CHECK(r.out.find("PASS check[1] x (value): x at t = 1: 0.54030230") != std::string::npos);
  CHECK(r.out.find(", expected 0.54030230") != std::string::npos);
  CHECK(r.out.find("PASS check[1] vel_x (max_abs): max |vel_x| = ") != std::string::npos);
  CHECK(r.out.find("checks: 2 passed, 0 failed (2 scenes)") != std::string::npos);
  CHECK(junit_counts(box, "report.xml") == "testsuites 2 0 0 2 0\n");
  // Classes Jenkins reads as package 'condyn' and the scene (it splits at the last dot: the
  // scene's path gave every class the name 'toml').
  const std::string xml = slurp(box.path("report.xml"));
  CHECK(xml.find("<testcase classname=\"condyn.a\" name=\"check[1] x (value)\"") !=
        std::string::npos);
  CHECK(xml.find("<testcase classname=\"condyn.b\"") != std::string::npos);
}

TEST_CASE("cli check: a JUnit report on standard output is the whole of it, the lines on stderr") {
  Sandbox box;
  box.write("a.toml", scene(kHolds));
  box.write("b.toml", scene(kFails));
  // Sandbox::run sends stdout to out.txt: what a CI step piping `--junit -` would parse.
  const Result r = box.run("check a.toml b.toml --junit -");
  CAPTURE(r.err);
  CHECK(r.code == 1);
  CHECK(junit_counts(box, "out.txt") == "testsuites 2 1 0 2 1\n");
  CHECK(r.err.find("FAIL check[1] x (value)") != std::string::npos);
  CHECK(r.err.find("wrote the JUnit report to standard output") != std::string::npos);
}

TEST_CASE("cli check and compare: the scene's warnings are shown, as run shows them") {
  Sandbox box;
  std::string text = scene("[[check]]\nquantity = \"x\"\nmax_abs = 2.0\n");
  text.replace(text.find("displacement = { x = 1.0 }"), 26, "displacement = { x = 1.0, y = 2e16 }");
  text.replace(text.find("dofs = [\"x\"]"), 12, "dofs = [\"x\", \"y\"]");
  text.replace(text.find("mass = [[1.0]]"), 14, "mass = [[1.0, 0.0], [0.0, 1.0]]");
  text.replace(text.find("stiffness = [[1.0]]"), 19, "stiffness = [[1.0, 0.0], [0.0, 1.0]]");
  text.replace(text.find("rtol = 1e-10"), 12, "rtol = 0.5");
  box.write("w.toml", text);
  const std::string far = "warning: [initial] displacements up to magnitude 2e+16";
  const Result r = box.run("check w.toml --junit report.xml");
  CAPTURE(r.out);
  CHECK(r.code == 0);
  CHECK(r.out.find("  " + far) != std::string::npos);
  CHECK(r.out.find("  warning: rtol 0.5 asks for fewer than 2 correct digits") !=
        std::string::npos);
  CHECK(slurp(box.path("report.xml")).find("<system-err>" + far) != std::string::npos);
  // compare: on stderr, without the scene's rtol (compare runs its own tolerances).
  const Result c = box.run("compare w.toml --tolerances 1e-6 --schemes ggl --no-plots");
  CAPTURE(c.err);
  CHECK(c.err.find("warning: w.toml: [initial] displacements up to magnitude 2e+16") !=
        std::string::npos);
  CHECK(c.err.find("rtol 0.5") == std::string::npos);
}

TEST_CASE("cli check: a check that fails: exit 1 and a JUnit failure") {
  Sandbox box;
  box.write("a.toml", scene(kHolds + kFails));
  const Result r = box.run("check a.toml --junit report.xml");
  CAPTURE(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("FAIL check[2] x (value): x at t = 1: 0.54030230") != std::string::npos);
  CHECK(r.out.find(", expected 0.5 +- 0.001 (off by 0.04030230") != std::string::npos);
  CHECK(r.out.find("checks: 1 passed, 1 failed") != std::string::npos);
  CHECK(junit_counts(box, "report.xml") == "testsuites 2 1 0 1 1\n");
}

TEST_CASE("cli check: bad input is exit 2 naming file, line and key, the other scenes still run") {
  Sandbox box;
  box.write("good.toml", scene(kHolds));
  box.write("typo.toml", scene("[[check]]\nquantity = \"y\"\nmax_abs = 1.0\n"));
  box.write("none.toml", scene(""));
  const Result r = box.run("check typo.toml none.toml good.toml --junit report.xml");
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find("ERROR typo.toml:14: check[1].quantity: no output column is named 'y'") !=
        std::string::npos);
  CHECK(r.out.find("ERROR none.toml: has no [[check]] table") != std::string::npos);
  CHECK(r.out.find("PASS check[1] x (value)") != std::string::npos);
  CHECK(r.out.find("checks: 1 passed, 0 failed, 2 scene(s) not checked (3 scenes)") !=
        std::string::npos);
  CHECK(junit_counts(box, "report.xml") == "testsuites 3 0 2 3 0\n");

  // Refused before the files the scene names are read (a matrix model's can take seconds).
  box.write("matrix.toml",
            "[model]\ntype = \"matrix\"\nmass = { file = \"absent_M.mtx\" }\n"
            "stiffness = { file = \"absent_K.mtx\" }\n[solve]\nt_end = 1.0\n");
  const Result matrix = box.run("check matrix.toml");
  CAPTURE(matrix.out);
  CHECK(matrix.code == 2);
  CHECK(matrix.out.find("ERROR matrix.toml: has no [[check]] table") != std::string::npos);
  CHECK(matrix.out.find("absent_") == std::string::npos);

  // A reference reaching past the run names its file; an empty scene name is named as such.
  box.write("late_ref.csv", "t,x\n0,1\n2.5,0\n");
  box.write("late.toml", scene("[[check]]\nquantity = \"x\"\nreference = { file = "
                               "\"late_ref.csv\" }\ntolerance = 1e-6\n"));
  const Result late = box.run("check late.toml ''");
  CAPTURE(late.out);
  CHECK(late.code == 2);
  CHECK(late.out.find("check[1].reference.file: late_ref.csv: its times run from 0 to 2.5, "
                      "outside the run [0, 2]") != std::string::npos);
  CHECK(late.out.find("ERROR '': an empty scene file name: name a scene file") !=
        std::string::npos);

  const Result missing = box.run("check nowhere.toml");
  CHECK(missing.code == 2);
  CHECK(missing.out.find("nowhere.toml: cannot open the scene file (No such file or directory)") !=
        std::string::npos);
  // The report path is checked before any run: a folder is refused, exit 2, nothing run.
  const Result folder = box.run("check good.toml --junit .");
  CHECK(folder.code == 2);
  CHECK(folder.out.find("PASS") == std::string::npos);
}

TEST_CASE("cli check: the JUnit report may not overwrite a file a scene reads") {
  Sandbox box;
  const std::string reference = "t,x\n0,1\n1,0.5403023058681398\n";
  box.write("ref.csv", reference);
  box.write("ref.toml", scene("[[check]]\nquantity = \"x\"\nreference = { file = \"ref.csv\" }\n"
                              "tolerance = 1e-3\n"));
  const Result r = box.run("check ref.toml --junit ref.csv");
  CHECK(r.code == 2);
  CHECK(r.err.find("--junit ref.csv: is ref.csv, an input of this command") != std::string::npos);
  CHECK(r.out.find("PASS") == std::string::npos);  // refused before the run
  CHECK(slurp(box.path("ref.csv")) == reference);
}

TEST_CASE("cli check: the JUnit report is well-formed UTF-8 whatever bytes a message quotes") {
  Sandbox box;
  // A reference file with a Latin-1 degree sign (0xB0): the refusal quotes the value.
  box.write("ref.csv", "t,x\n0,1\n1,0.54\xb0\n");
  box.write("latin.toml", scene("[[check]]\nquantity = \"x\"\nreference = { file = \"ref.csv\" }\n"
                                "tolerance = 1e-6\n"));
  const Result r = box.run("check latin.toml --junit report.xml");
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(junit_counts(box, "report.xml") == "testsuites 1 0 1 1 0\n");
  const std::string xml = slurp(box.path("report.xml"));
  CHECK(xml.find("0.54\xef\xbf\xbd") != std::string::npos);  // U+FFFD in its place
}

TEST_CASE("cli check and run: a check's column must exist in this model's output") {
  Sandbox box;
  // acc_abs_ columns exist under [ground_motion] only, as [output] quantities says.
  box.write("abs.toml", scene("[[check]]\nquantity = \"acc_abs_x\"\nmax_abs = 1.0\n"));
  const Result abs = box.run("check abs.toml");
  CHECK(abs.code == 2);
  CHECK(abs.out.find("check[1].quantity: 'acc_abs_x' needs [ground_motion]") != std::string::npos);
  // run refuses a bad check as check does (it refused a missing reference file already).
  box.write("typo.toml", scene("[[check]]\nquantity = \"y\"\nmax_abs = 1.0\n"));
  const Result run = box.run("run typo.toml --out r.csv");
  CHECK(run.code == 2);
  CHECK(run.err.find("check[1].quantity: no output column is named 'y'") != std::string::npos);
  CHECK(box.run("run abs.toml --out r.csv").code == 2);
  // So do info and compare.
  const Result info = box.run("info typo.toml");
  CHECK(info.code == 2);
  CHECK(info.err.find("check[1].quantity: no output column is named 'y'") != std::string::npos);
  const Result compare = box.run("compare typo.toml --tolerances 1e-4 --no-plots");
  CHECK(compare.code == 2);
  CHECK(compare.err.find("check[1].quantity: no output column is named 'y'") != std::string::npos);
  box.write("good.toml", scene(kHolds));
  CHECK(box.run("run good.toml --out r.csv").code == 0);
}

TEST_CASE("cli check: a reference of one row is compared at its time") {
  Sandbox box;
  box.write("one.csv", "t,x\n1,0.5403023058681398\n");  // cos(1)
  box.write("one.toml", scene("[[check]]\nquantity = \"x\"\nreference = { file = \"one.csv\" }\n"
                              "tolerance = 1e-7\n"));
  const Result r = box.run("check one.toml");
  CAPTURE(r.out);
  CHECK(r.code == 0);
  box.write("off.csv", "t,x\n1,0.54\n");
  box.write("off.toml", scene("[[check]]\nquantity = \"x\"\nreference = { file = \"off.csv\" }\n"
                              "tolerance = 1e-7\n"));
  CHECK(box.run("check off.toml").code == 1);
}

TEST_CASE("cli check: a reference's first column is the time, headed t") {
  // A row number first was read as the times: correct data gave FAIL (0.337), and a file
  // without a t column passed as if its first values column were time.
  Sandbox box;
  // A row index before a column t is refused as for every table (models/core/time_table.cpp).
  box.write("bad.csv", "idx,t,x\n0,0,1\n1,0.5,0.8775825618903728\n");
  box.write("bad.toml", scene("[[check]]\nquantity = \"x\"\nreference = { file = \"bad.csv\" }\n"
                              "tolerance = 1e-7\n"));
  const Result index = box.run("check bad.toml");
  CHECK(index.code == 2);
  const std::string index_said = index.out + index.err;
  CHECK_MESSAGE(
      index_said.find("bad.toml:16: check[1].reference.file: bad.csv:1: the first column "
                      "holds the time, but it is 'idx' and column 2 is 't'") != std::string::npos,
      index_said);
  for (const std::string& csv : {std::string("x_ref,x\n1,0.5403023058681398\n")}) {
    CAPTURE(csv);
    box.write("bad.csv", csv);
    box.write("bad.toml", scene("[[check]]\nquantity = \"x\"\nreference = { file = \"bad.csv\" }\n"
                                "tolerance = 1e-7\n"));
    const Result r = box.run("check bad.toml");
    CHECK(r.code == 2);
    const std::string said = r.out + r.err;
    CHECK_MESSAGE(said.find("bad.toml:16: check[1].reference.file: bad.csv: its first column is "
                            "headed") != std::string::npos,
                  said);
    CHECK_MESSAGE(said.find("a reference's first column is the time, headed t (as in t,x)") !=
                      std::string::npos,
                  said);
  }
}

TEST_CASE("cli check: a run that fails is an error of its scene (exit 1)") {
  Sandbox box;
  box.write("a.toml", scene("[[check]]\nquantity = \"x\"\nmax_abs = 1.0\n"));
  const Result r = box.run("check a.toml --scheme index1 --junit report.xml");
  CHECK(r.code == 0);  // the base case runs
  std::string tight = scene("[[check]]\nquantity = \"x\"\nmax_abs = 1.0\n");
  tight.insert(tight.find("rtol"), "max_steps = 3\n");
  box.write("b.toml", tight);
  const Result f = box.run("check b.toml --junit report.xml");
  CAPTURE(f.out);
  CHECK(f.code == 1);
  CHECK(f.out.find("ERROR the run failed: step budget exhausted") != std::string::npos);
  CHECK(junit_counts(box, "report.xml") == "testsuites 1 0 1 1 0\n");
}

TEST_CASE(
    "cli compare: a failed run makes the exit 1 unless --allow-failures, no study by default") {
  Sandbox box;
  box.write("s.toml", scene(""));
  const std::string args =
      "compare s.toml --tolerances 1e-4 --schemes index1,ggl --repeats 1 "
      "--no-plots --max-steps 5 --out-dir out";
  const Result r = box.run(args);
  CAPTURE(r.err);
  CHECK(r.code == 1);
  CHECK(r.err.find("error: 4 runs of the comparison failed") != std::string::npos);
  // runs.csv holds the sweep's two; the two drift-history runs are in runs.json.
  CHECK(r.err.find("out/runs.csv, and for the 2 drift-history runs out/runs.json)") !=
        std::string::npos);
  CHECK(slurp(box.path("out/runs.csv")).find("step budget") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(box.path("out/baumgarte_study.csv")));
  const Result tolerated = box.run(args + " --allow-failures");
  CHECK(tolerated.code == 0);
  CHECK(tolerated.err.find("tolerated by --allow-failures") != std::string::npos);

  const Result study = box.run(
      "compare s.toml --tolerances 1e-4 --schemes baumgarte --repeats 1 --no-plots "
      "--baumgarte-study --out-dir out2");
  CHECK(study.code == 0);
  // The oscillator has no constraint: the study has nothing to stabilize and writes an empty grid.
  CHECK(slurp(box.path("out2/baumgarte_study.csv")).rfind("alpha,beta,default,status", 0) == 0);
  CHECK(study.err.find("Baumgarte study: not run (the scene has no constraints") !=
        std::string::npos);
  // Asked for, the study runs whatever --schemes lists: its 16 points and a header.
  box.write("c.toml", condyn::test::kTwoMassesScene);
  CHECK(box.run("compare c.toml --tolerances 1e-4 --schemes ggl --repeats 1 --no-plots "
                "--baumgarte-study --out-dir out3")
            .code == 0);
  const std::string grid = slurp(box.path("out3/baumgarte_study.csv"));
  CHECK(std::count(grid.begin(), grid.end(), '\n') == 17);

  // Figures an earlier comparison drew describe other runs: gone once this one writes its files
  // (drawn again from them, or not at all under --no-plots); the user's own files stay.
  for (const char* old : {"out2/drift.png", "out2/work_precision.pdf", "out2/baumgarte_study.png",
                          "out2/notes.png"}) {
    box.write(old, "an earlier figure");
  }
  CHECK(box.run("compare s.toml --tolerances 1e-4 --schemes ggl --repeats 1 --no-plots "
                "--out-dir out2")
            .code == 0);
  CHECK_FALSE(std::filesystem::exists(box.path("out2/drift.png")));
  CHECK_FALSE(std::filesystem::exists(box.path("out2/work_precision.pdf")));
  CHECK_FALSE(std::filesystem::exists(box.path("out2/baumgarte_study.png")));
  CHECK(std::filesystem::exists(box.path("out2/notes.png")));
}

TEST_CASE("cli check: a run killed by a time limit keeps the verdicts already printed") {
  // stdout to a file is fully buffered, and SIGTERM discards the buffer: every PASS/FAIL line
  // of the scenes done was lost before each scene's lines were flushed.
  Sandbox box;
  box.write("quick.toml", scene(kHolds));
  // The oscillator for 10^6 s at rtol 1e-10: millions of steps, stopped long before its end.
  std::string endless = scene("[[check]]\nquantity = \"x\"\nmax_abs = 2.0\n");
  endless = condyn::test::replace(endless, "t_end = 2.0\noutput_step = 0.1",
                                  "t_end = 1e6\noutput_step = 1000.0");
  box.write("endless.toml", endless);
  const std::string cmd = "cd '" + box.path("").string() + "' && timeout 3 '" +
                          std::string(CONDYN_BINARY) +
                          "' check quick.toml endless.toml > killed.txt 2>&1";
  const int status = std::system(cmd.c_str());
  CHECK(WEXITSTATUS(status) == 124);  // timeout's code: the run was stopped
  const std::string out = slurp(box.path("killed.txt"));
  CAPTURE(out);
  CHECK(out.find("PASS check[1] x (value)") != std::string::npos);
}

}  // namespace test_cli_check
