// SuiteSparseQR is loaded only by the scenes that need it (models/core/sparse_qr.hpp): a small
// scene runs without it, a constraint group beyond the dense rank check loads it. The dynamic
// loader's own trace (LD_DEBUG=files) says which libraries a process opened.

#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/lattice_scene.hpp"

using condyn::test::lattice;
using condyn::test::Result;
using condyn::test::Sandbox;

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
