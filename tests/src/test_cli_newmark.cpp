// The Newmark family from the command line: `run --scheme S --step h` writes the columns the
// other schemes write (reactions included), without --step it controls its steps by error, and
// bad parameters or steps exit 2 naming the key.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_newmark {

using condyn::test::Result;
using condyn::test::Sandbox;

namespace {

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("run under the Newmark family writes the other schemes' columns") {
  const Sandbox box;
  box.write("p.toml", condyn::test::kFixedStepPendulum);
  const Result ggl = box.run("run p.toml --scheme ggl --out ggl.csv");
  REQUIRE(ggl.code == 0);
  for (const char* scheme : {"newmark", "hht", "generalized_alpha"}) {
    CAPTURE(scheme);
    const std::string out = std::string(scheme) + ".csv";
    const Result r = box.run(std::string("run p.toml --scheme ") + scheme + " --out " + out);
    CHECK(r.code == 0);
    CHECK(first_line(condyn::test::slurp(box.path(out))) ==
          first_line(condyn::test::slurp(box.path("ggl.csv"))));
    CHECK(contains(r.out + r.err, std::string(scheme) + ": alpha_m"));  // the parameters noted
  }
  // --step overrides [solve] step.
  CHECK(box.run("run p.toml --scheme hht --step 0.005 --out s.csv").code == 0);
}

TEST_CASE("the Newmark family's bad parameters and steps exit 2 naming the key") {
  const Sandbox box;
  std::string bad_alpha = condyn::test::kFixedStepPendulum;
  bad_alpha.replace(bad_alpha.find("step = 0.01"), 11,
                    "step = 0.01\nscheme = \"hht\"\nhht = { alpha = -0.5 }");
  box.write("a.toml", bad_alpha);
  const Result a = box.run("run a.toml --out a.csv");
  CHECK(a.code == 2);
  CHECK(contains(a.err, "a.toml:13: solve.hht.alpha: must lie in [-1/3, 0]"));
  box.write("p.toml", condyn::test::kFixedStepPendulum);
  const Result big = box.run("run p.toml --scheme newmark --step 5 --out b.csv");
  CHECK(big.code == 2);
  CHECK(contains(big.err, "solve.step"));
  std::string beta = condyn::test::kFixedStepPendulum;
  beta.replace(beta.find("step = 0.01"), 11, "step = 0.01\nnewmark = { beta = 0.2 }");
  box.write("beta.toml", beta);
  const Result b = box.run("run beta.toml --scheme newmark --out beta.csv");
  CHECK(b.code == 2);
  CHECK(contains(b.err, "beta.toml:12: solve.newmark.beta: must be >= gamma/2 = 0.25"));
  CHECK(!std::filesystem::exists(box.path("beta.csv")));
}

TEST_CASE("the Newmark family without a step runs with error-controlled steps") {
  const Sandbox box;
  std::string no_step = condyn::test::kFixedStepPendulum;
  no_step.replace(no_step.find("step = 0.01"), 11, "rtol = 1e-6\natol = 1e-8");
  box.write("n.toml", no_step);
  for (const char* scheme : {"newmark", "hht", "generalized_alpha"}) {
    CAPTURE(scheme);
    const Result r =
        box.run(std::string("run n.toml --scheme ") + scheme + " --out " + scheme + ".csv");
    CHECK(r.code == 0);
    CHECK(contains(r.out + r.err, "error-controlled steps"));
    const Result i = box.run(std::string("info n.toml --scheme ") + scheme);
    CHECK(i.code == 0);
  }
}

TEST_CASE(
    "info names the Newmark family's parameters and step, and compare sets them no rtol target") {
  const Sandbox box;
  box.write("p.toml", condyn::test::kFixedStepPendulum);
  // info: which scheme and why (requested), with the parameters and the fixed step it would use.
  const Result info = box.run("info p.toml --scheme hht");
  REQUIRE(info.code == 0);
  CHECK(contains(info.out, "scheme: hht (requested)"));
  CHECK(contains(info.out,
                 "hht: alpha_m = 0, alpha_f = 0.05, beta = 0.275625, gamma = 0.55, "
                 "fixed step 0.01"));
  // compare: under a fixed step rtol is only Newton's tolerance, so the runs have no error target
  // ("-", empty in runs.csv, null in runs.json) and are never marked over it: the pendulum's
  // newmark error, 1.9e-2 in the reactions at h = 0.01, was 1.9e4 times rtol 1e-6 and failed
  // --fail-above 1e4 before.
  const Result cmp = box.run(
      "compare p.toml --schemes ggl,newmark --tolerances 1e-6 --repeats 1 --fail-above 1e4 "
      "--no-plots --out-dir cmp");
  CHECK(cmp.code == 0);
  const std::string json = condyn::test::slurp(box.path("cmp/runs.json"));
  CHECK_FALSE(contains(json, "nan"));
  CHECK(contains(json, "\"scheme\": \"newmark\""));
  CHECK(contains(json, "\"error_target\": null"));
}

TEST_CASE("info, check and compare take --step as run does, and refuse a bad one") {
  const Sandbox box;
  std::string no_step = condyn::test::kFixedStepPendulum;
  no_step.replace(no_step.find("step = 0.01"), 11, "");
  // The index-3 position rows hold to roundoff under the family (docs/schemes.md).
  box.write("c.toml", no_step + "[[check]]\nquantity = \"drift_position\"\nmax_abs = 1e-9\n");
  const Result info = box.run("info c.toml --scheme generalized_alpha --step 0.005");
  CHECK(info.code == 0);
  CHECK(contains(info.out, "step 0.005"));  // "fixed step 0.005", wrapped at 100 columns
  const Result check = box.run("check c.toml --scheme hht --step 0.01");
  CHECK(check.code == 0);
  CHECK(contains(check.out, "(hht, 50 steps"));
  // Without a step: error-controlled steps. A step beyond t_end: bad input (exit 2) naming the
  // key, as under run; check exited 1 before, as for a failed run.
  CHECK(box.run("check c.toml --scheme hht").code == 0);
  const Result bad = box.run("check c.toml --scheme hht --step 5");
  CHECK(bad.code == 2);
  CHECK(contains(bad.out + bad.err, "solve.step"));
  const Result bad_info = box.run("info c.toml --scheme hht --step 5");
  CHECK(bad_info.code == 2);
  CHECK(contains(bad_info.err, "solve.step"));
  const Result cmp = box.run(
      "compare c.toml --schemes ggl,generalized_alpha --step 0.01 --tolerances 1e-6 --repeats 1 "
      "--no-plots --out-dir cmp");
  CHECK(cmp.code == 0);
  CHECK(contains(cmp.out, "generalized_alpha  1e-06"));
  const Result bad_cmp = box.run(
      "compare c.toml --schemes generalized_alpha --step 5 --tolerances 1e-6 --out-dir cmp2");
  CHECK(bad_cmp.code == 2);
  CHECK(contains(bad_cmp.err, "solve.step"));
}

}  // namespace test_cli_newmark
