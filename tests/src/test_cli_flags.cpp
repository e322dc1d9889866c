// Command-line values are read strictly: a number flag takes a whole decimal number in its range,
// every message is short and names the flag, and `--version` answers.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "tests/cli_sandbox.hpp"

namespace test_cli_flags {

using condyn::test::Result;
using condyn::test::Sandbox;

namespace {

const std::string kScene = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 2.0]]
stiffness = [[3.0, -1.0], [-1.0, 1.0]]
[solve]
t_end = 1.0
output_step = 0.25
)";

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// A usage message is a line or two, not a 300-digit range: a bound with a reason.
constexpr std::size_t kShortMessage = 200;

}  // namespace

TEST_CASE("number flags take whole decimal numbers in their range, with a short message") {
  const Sandbox box;
  box.write("s.toml", kScene);
  struct Case {
    std::string args, flag, says;
  };
  const Case cases[] = {
      {"run s.toml --rtol abc", "--rtol", "'abc' is not a decimal number"},
      {"run s.toml --rtol 0x10", "--rtol", "'0x10' is not a decimal number"},
      {"run s.toml --rtol 1e-6x", "--rtol", "'1e-6x' is not a decimal number"},
      {"run s.toml --rtol nan", "--rtol", "'nan' is not a decimal number"},
      {"run s.toml --rtol inf", "--rtol", "'inf' is not a decimal number"},
      {"run s.toml --rtol 1", "--rtol",
       "1 is out of range: a relative tolerance lies in [1e-15, 1)"},
      {"run s.toml --rtol 1e-16", "--rtol", "out of range"},
      {"run s.toml --rtol -1e-6", "--rtol", "out of range"},
      {"run s.toml --atol 0x1", "--atol", "'0x1' is not a decimal number"},
      {"run s.toml --atol 1e999", "--atol", "'1e999' is not a decimal number"},
      {"run s.toml --atol 0", "--atol", "an absolute tolerance is at least 1e-100"},
      {"compare --tolerances 1e-3x", "--tolerances", "'1e-3x' is not a decimal number"},
      {"compare --tolerances 1e-4,0x10", "--tolerances", "'0x10' is not a decimal number"},
      {"compare --tolerances 1", "--tolerances", "out of range"},
      {"compare --drift-rtol abc", "--drift-rtol", "'abc' is not a decimal number"},
      {"compare --drift-rtol 1", "--drift-rtol", "out of range"},
      {"compare --repeats 0x10", "--repeats", "not a whole number in [1, 100]"},
      {"compare --repeats 2.5", "--repeats", "not a whole number in [1, 100]"},
      {"compare --repeats 0", "--repeats", "not a whole number in [1, 100]"},
      {"compare --schemes ggl,foo", "--schemes", "unknown scheme 'foo'"},
      {"info s.toml --scheme foo", "--scheme", "unknown scheme 'foo'"},
      // Lists: a stray comma, an item twice, an empty value are mistakes, not the default.
      {"compare --tolerances 1e-3,,1e-4", "--tolerances", "an empty item in '1e-3,,1e-4'"},
      {"compare --tolerances 1e-3,1e-3", "--tolerances", "'1e-3' is listed twice"},
      {"compare --tolerances 1e-3,0.001", "--tolerances", "'0.001' is listed twice"},
      // Whole numbers up to the bound the help gives; beyond it, and blanks, refused.
      {"run s.toml --max-steps 2147483648 --out r.csv", "--max-steps",
       "'2147483648' is not a whole number in [1, 2147483647]"},
      {"run s.toml --max-steps 99999999999999999999999 --out r.csv", "--max-steps",
       "not a whole number in [1, 2147483647]"},
      {"run s.toml --scheme '\t' --out r.csv", "--scheme", "is empty"},  // a tab
      {"run s.toml --out ' '", "--out", "an empty name"},
      {"compare ''", "scene", "is empty: name a scene file, or leave it out"},
      // A flag where a value was due: --out took '--scheme', and ggl was left over.
      {"run s.toml --out --scheme ggl", "--out", "a value is missing ('--scheme' is a flag"},
      {"run s.toml --scheme --out r.csv", "--scheme", "a value is missing ('--out' is a flag)"},
      // Below the double range a number is still one: its range is what is wrong.
      {"run s.toml --atol 1e-320 --out r.csv", "--atol",
       "1e-320 is out of range: an absolute tolerance is at least 1e-100"},
      {"run s.toml --atol 1e400 --out r.csv", "--atol",
       "'1e400' is not a decimal number within the double range"},
      {"compare --tolerances ''", "--tolerances", "is empty (leave the flag out instead)"},
      {"compare --schemes ggl,ggl", "--schemes", "'ggl' is listed twice"},
      {"compare --out-dir ''", "--out-dir", "is empty"},
      {"stress --families ''", "--families", "is empty"},
      {"stress --families stiffness,", "--families", "an empty item"},
      {"stress --schemes ggl,", "--schemes", "an empty item"},
      {"plot r.csv --dofs ''", "--dofs", "is empty"},
      {"check s.toml --junit ''", "--junit", "is empty"},
      {"run s.toml --scheme '' --out r.csv", "--scheme", "is empty"},
      {"run s.toml --constraints '' --out r.csv", "--constraints", "is empty"},
      {"info s.toml --scheme ''", "--scheme", "is empty"},
      {"info s.toml --constraints ''", "--constraints", "is empty"},
      // A treatment of the multiplier schemes: under another it was silently ignored.
      {"run s.toml --scheme elimination --constraints mixed --out r.csv", "--constraints",
       "applies to the multiplier schemes (index1, baumgarte, ggl, index2, index3), the Newmark "
       "family (newmark, hht, generalized_alpha) and auto, not to elimination"},
      {"run s.toml --scheme penalty --constraints multipliers --out r.csv", "--constraints",
       "not to penalty"},
      {"info s.toml --scheme projection --constraints mixed", "--constraints", "not to projection"},
      {"check s.toml --scheme ''", "--scheme", "is empty"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.args);
    const Result r = box.run(c.args);
    CAPTURE(r.err);
    CHECK(r.code == 2);
    CHECK(contains(r.err, c.flag + ": "));
    CHECK(contains(r.err, c.says));
    CHECK(r.err.size() < kShortMessage + 40);  // + "Run with --help for more information."
    CHECK(!contains(r.err, "[1/"));            // compare refused before its first run
  }
  // An option before the command that condyn does not have; a report that cannot be written.
  for (const char* unknown : {"-x", "--versio"}) {
    const Result r = box.run(unknown);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "error: unknown option '" + std::string(unknown) + "'"));
  }
  const int full = std::system(("cd '" + box.path("").string() + "' && '" + CONDYN_BINARY +
                                "' info s.toml > /dev/full 2> full.txt")
                                   .c_str());
  CHECK((WIFEXITED(full) && WEXITSTATUS(full) == 1));
  CHECK(
      contains(condyn::test::slurp(box.path("full.txt")), "error: writing standard output failed"));
  // What stays accepted.
  CHECK(box.run("run s.toml --out ./--r.csv").code == 0);
  CHECK(box.run("run s.toml --max-steps 2147483647 --out r.csv").code == 0);
  CHECK(box.run("run s.toml --max-steps +01000000000 --out r.csv").code == 0);
  CHECK(box.run("run s.toml --rtol 1e-6 --atol 1E-9 --out r.csv").code == 0);
  CHECK(box.run("run s.toml --rtol .001 --atol 2 --out r.csv").code == 0);
  const Result loose = box.run("run s.toml --rtol 0.5 --out r.csv");
  CHECK(loose.code == 0);
  CHECK(contains(loose.err, "warning: s.toml: rtol 0.5 asks for fewer than 2 correct digits"));
}

TEST_CASE("[solve] rtol has the command line's range") {
  const Sandbox box;
  box.write("one.toml", kScene + "rtol = 1.0\n");
  const Result r = box.run("run one.toml --out r.csv");
  CHECK(r.code == 2);
  CHECK(contains(r.err, "one.toml:9: solve.rtol: is out of range: a relative tolerance lies in"));
  box.write("tiny.toml", kScene + "rtol = 1e-300\n");
  CHECK(box.run("run tiny.toml --out r.csv").code == 2);
  // A loose one from the scene is warned of as one from --rtol is.
  box.write("loose.toml", kScene + "rtol = 0.05\n");
  const Result loose = box.run("run loose.toml --out r.csv");
  CHECK(loose.code == 0);
  CHECK(contains(loose.err, "warning: loose.toml: rtol 0.05 asks for fewer than 2 correct digits"));
}

TEST_CASE("a word that is no command is named, with the commands") {
  const Sandbox box;
  const Result r = box.run("bogus s.toml");
  CHECK(r.code == 2);
  CHECK(contains(r.err,
                 "error: 'bogus' is not a command (the commands: run, info, compare, check, "
                 "plot, stress, validate, sweep, modes;"));
}

TEST_CASE("an option given twice is named, with the count") {
  Sandbox box;
  box.write("s.toml", kScene);
  for (const char* args :
       {"run s.toml --rtol 1e-6 --rtol 1e-7", "run s.toml --out a.csv --out b.csv",
        "compare s.toml --tolerances 1e-6 --tolerances 1e-7"}) {
    CAPTURE(args);
    const Result r = box.run(args);
    CHECK(r.code == 2);
    const std::string flag = std::string(args).substr(std::string(args).find("--"));
    CHECK(contains(r.err,
                   "error: " + flag.substr(0, flag.find(' ')) + " is given 2 times; give it once"));
  }
  CHECK_FALSE(std::filesystem::exists(box.path("a.csv")));
  CHECK_FALSE(std::filesystem::exists(box.path("b.csv")));
}

TEST_CASE("--version prints the program's version") {
  const Sandbox box;
  const Result r = box.run("--version");
  CHECK(r.code == 0);
  CHECK(std::regex_match(r.out, std::regex("condyn [0-9]+\\.[0-9]+\\.[0-9]+\n")));
}

TEST_CASE("--scheme that takes no [solve] constraints sets the scene's aside, and says so") {
  // A file pairing constraints with such a scheme is refused; an override (as compare's and a
  // user's study of one scene under each scheme) runs, with a warning naming what it set aside.
  const Sandbox box;
  const std::string tied = kScene + "scheme = \"ggl\"\nconstraints = \"mixed\"\n" +
                           "[[constraint]]\nterms = { a = 1.0, b = -1.0 }\n" +
                           "[[check]]\nquantity = \"a\"\nmax_abs = 10.0\n";
  box.write("s.toml", tied);
  for (const char* args : {"run s.toml --scheme elimination --out r.csv",
                           "info s.toml --scheme penalty", "check s.toml --scheme projection"}) {
    CAPTURE(args);
    const Result r = box.run(args);
    const std::string said = r.out + r.err;
    CAPTURE(said);
    CHECK(contains(said, "warning: "));
    CHECK(contains(said,
                   "[solve] constraints = \"mixed\" is set aside: it applies to the "
                   "multiplier schemes"));
  }
  CHECK(box.run("run s.toml --scheme elimination --out r.csv").code == 0);
  // Under a multiplier scheme it holds, without a word.
  const Result kept = box.run("run s.toml --scheme index1 --out r.csv");
  CHECK(kept.code == 0);
  CHECK_FALSE(contains(kept.err, "set aside"));
  // The same pair written in the file is refused, as before.
  box.write("both.toml", kScene + "scheme = \"elimination\"\nconstraints = \"mixed\"\n");
  CHECK(box.run("run both.toml --out r.csv").code == 2);
}

}  // namespace test_cli_flags
