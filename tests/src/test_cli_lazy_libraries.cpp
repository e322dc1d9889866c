// SuiteSparseQR, CHOLMOD and OpenBLAS are loaded only by the scenes that need them
// (models/core/load_library.hpp): a small scene runs without SuiteSparseQR, a constraint group
// beyond the dense rank check loads it; only a run that factors with CHOLMOD loads CHOLMOD and
// OpenBLAS, OpenBLAS first so that CHOLMOD's BLAS calls bind to it, and one that cannot load them
// is told which. The dynamic loader's own trace (LD_DEBUG=files, bindings) says which libraries a
// process opened and where its symbols went.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"
#include "tests/lattice_scene.hpp"

namespace test_cli_lazy_libraries {

using condyn::test::lattice;
using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

/// The command run with the loader's trace of the files it opens on standard error.
Result traced(const Sandbox& box, const std::string& args) {
  ::setenv("LD_DEBUG", "files", 1);
  Result r = box.run(args);
  ::unsetenv("LD_DEBUG");
  return r;
}

bool opened(const Result& r, const std::string& library) {
  return r.err.find("file=" + library) != std::string::npos;
}

/// Ties ux_k = uy_k and uy_k = ux_(k+1) over nodes first … last: one connected group of
/// 2 (last - first) + 1 rows over 2 (last - first + 1) DOFs.
std::string chain(int first, int last) {
  std::string c;
  int row = 0;
  for (int node = first; node <= last; ++node) {
    const std::string x = "ux" + std::to_string(node), y = "uy" + std::to_string(node);
    c += "[[constraint]]\nname = \"t" + std::to_string(++row) + "\"\nterms = { " + x + " = 1.0, " +
         y + " = -1.0 }\n";
    if (node < last) {
      c += "[[constraint]]\nname = \"t" + std::to_string(++row) + "\"\nterms = { " + y +
           " = 1.0, ux" + std::to_string(node + 1) + " = -1.0 }\n";
    }
  }
  return c;
}

}  // namespace

TEST_CASE("SuiteSparseQR is loaded only when a constraint group needs the sparse rank check") {
  Sandbox box;
  const Result version = traced(box, "--version");
  REQUIRE(version.code == 0);
  CHECK(opened(version, "libc.so"));  // the trace works
  CHECK_FALSE(opened(version, "libspqr"));
  CHECK_FALSE(opened(version, "liblapack"));

  // 17 ties over 18 DOFs of the top row (306 constraint-DOF pairs): the dense QR decides.
  box.write("small.toml", lattice(10, 10, chain(92, 100), "scheme = \"index1\"\n"));
  const Result small = traced(box, "info small.toml");
  CHECK(small.code == 0);
  CHECK_FALSE(opened(small, "libspqr"));

  // 137 ties over 138 DOFs: 18,906 constraint-DOF pairs, beyond the dense block (1e4).
  box.write("large.toml", lattice(70, 70, chain(4832, 4900), "scheme = \"index1\"\n"));
  const Result large = traced(box, "info large.toml");
  CHECK(large.code == 0);
  CHECK(opened(large, "libspqr"));
}

namespace {

/// A 12 × 12 lattice with a tie and a step load under elimination, displacements written, with
/// `solve_keys`.
std::string elimination_scene(const std::string& solve_keys) {
  return lattice(12, 12,
                 "[[constraint]]\nname = \"tie\"\nterms = { uy144 = 1.0, uy133 = -1.0 }\n"
                 "[[load]]\ndof = \"uy144\"\nvalue = { type = \"step\", amplitude = -1.0 }\n"
                 "[output]\nquantities = [\"displacement\"]\n",
                 "scheme = \"elimination\"\nrtol = 1e-8\natol = 1e-10\n" + solve_keys);
}

/// The numbers of a result CSV, row after row, its header left out.
std::vector<double> csv_values(const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  std::vector<double> values;
  while (std::getline(lines, line)) {
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) values.push_back(std::stod(cell));
  }
  return values;
}

}  // namespace

TEST_CASE("CHOLMOD and OpenBLAS are loaded only by a run that factors with CHOLMOD") {
  Sandbox box;
  const Result version = traced(box, "--version");
  REQUIRE(version.code == 0);
  CHECK(opened(version, "libc.so"));  // the trace works
  CHECK_FALSE(opened(version, "libcholmod"));
  CHECK_FALSE(opened(version, "libopenblas"));

  // The default (auto on the full Jacobian) and KLU named: neither library.
  for (const char* keys : {"", "linear_solver = \"klu\"\n"}) {
    CAPTURE(keys);
    box.write("k.toml", elimination_scene(keys));
    const Result klu = traced(box, "run k.toml --out k.csv");
    REQUIRE(klu.code == 0);
    CHECK_FALSE(opened(klu, "libcholmod"));
    CHECK_FALSE(opened(klu, "libopenblas"));
  }

  box.write("c.toml", elimination_scene("linear_solver = \"cholmod\"\n"));
  const Result chol = traced(box, "run c.toml --out c.csv");
  REQUIRE(chol.code == 0);
  CHECK(opened(chol, "libcholmod"));
  // OpenBLAS first, so that CHOLMOD's BLAS calls bind to it whatever libblas.so.3 is.
  CHECK(chol.err.find("file=libopenblas") < chol.err.find("file=libcholmod"));

  // The same answer: the same Newton iterations with another backward-stable factorization
  // differ by roundoff amplified through the error control, inside 10 rtol (rtol = 1e-8) of
  // the largest value.
  const std::vector<double> a = csv_values(slurp(box.path("k.csv")));
  const std::vector<double> b = csv_values(slurp(box.path("c.csv")));
  REQUIRE(a.size() == b.size());
  REQUIRE_FALSE(a.empty());
  double scale = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    scale = std::max(scale, std::abs(a[i]));
    difference = std::max(difference, std::abs(a[i] - b[i]));
  }
  constexpr double kRtol = 1e-8;
  CHECK(difference <= 10 * kRtol * scale);
}

TEST_CASE("CHOLMOD's BLAS and LAPACK calls bind to OpenBLAS") {
  Sandbox box;
  box.write("c.toml", elimination_scene("linear_solver = \"cholmod\"\n"));
  // The trace in files of its own (bindings.PID), apart from the shell's that runs the command.
  ::setenv("LD_DEBUG", "bindings", 1);
  ::setenv("LD_DEBUG_OUTPUT", box.path("bindings").c_str(), 1);
  const Result r = box.run("run c.toml --out c.csv");
  ::unsetenv("LD_DEBUG_OUTPUT");
  ::unsetenv("LD_DEBUG");
  REQUIRE(r.code == 0);
  std::string trace;
  for (const auto& file : std::filesystem::directory_iterator(box.path("."))) {
    if (file.path().filename().string().rfind("bindings.", 0) == 0) trace += slurp(file.path());
  }
  // The loader's line: "binding file …/libcholmod.so.3 [0] to …/libopenblas.so.0 [0]: normal
  // symbol `dgemm_'"; the supernodal factorization's BLAS and LAPACK routines.
  for (const char* symbol : {"dgemm_", "dsyrk_", "dtrsm_", "dpotrf_"}) {
    CAPTURE(symbol);
    std::istringstream lines(trace);
    bool openblas = false, other = false;
    for (std::string line; std::getline(lines, line);) {
      if (line.find("libcholmod") == std::string::npos ||
          line.find(std::string("`") + symbol + "'") == std::string::npos) {
        continue;
      }
      (line.find("libopenblas") != std::string::npos ? openblas : other) = true;
    }
    CHECK(openblas);
    CHECK_FALSE(other);
  }
}

TEST_CASE("a CHOLMOD or OpenBLAS that cannot be loaded: cholmod refused naming the key") {
  // An empty file of the library's name (Debian 12's SONAMEs) first on the loader's path: dlopen
  // fails on it ("file too short") as on a missing or broken installation.
  for (const char* library : {"libopenblas.so.0", "libcholmod.so.3"}) {
    CAPTURE(library);
    Sandbox box;
    std::filesystem::create_directories(box.path("lib"));
    box.write(std::string("lib/") + library, "");
    box.write("c.toml", elimination_scene("linear_solver = \"cholmod\"\n"));
    box.write("a.toml", elimination_scene("newton = \"condensed\"\n"));
    ::setenv("LD_LIBRARY_PATH", box.path("lib").c_str(), 1);
    const Result named = box.run("run c.toml --out c.csv");
    const Result automatic = box.run("run a.toml --out a.csv");
    ::unsetenv("LD_LIBRARY_PATH");
    CHECK(named.code == 2);
    CHECK(named.err.find("c.toml:") != std::string::npos);
    CHECK(named.err.find("solve.linear_solver") != std::string::npos);
    CHECK(named.err.find(std::string("(") + library + ")") != std::string::npos);
    CHECK(named.err.find("install Debian's") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(box.path("c.csv")));
    // auto falls back to KLU and says why.
    CHECK(automatic.code == 0);
    CHECK((automatic.out + automatic.err).find(std::string("(") + library + ")") !=
          std::string::npos);
    CHECK(std::filesystem::exists(box.path("a.csv")));
  }
}

}  // namespace test_cli_lazy_libraries
