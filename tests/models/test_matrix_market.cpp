// Issue 12, item 4: matrices, constraint blocks and load patterns from Matrix Market files, and
// Rayleigh damping (scene-format.md, "Matrices and vectors from files"). The strict reader, every
// scene key, the refusals (each naming the scene file, the key and the .mtx file's line), and a
// model read from files that runs exactly as the same model written inline.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/memory_estimate.hpp"
#include "models/core/model.hpp"
#include "models/scene/matrix_market.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_matrix_market {

using condyn::test::Sandbox;

namespace {

/// The line a malformed text is refused at, and its message.
std::pair<int, std::string> market_error(const std::string& text,
                                         const MarketExpectation& expect = {}) {
  try {
    (void)parse_matrix_market(text, expect);
  } catch (const MatrixMarketError& e) {
    return {e.line(), e.what()};
  }
  return {-1, ""};
}

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// The scene's SceneError message when parsing and building refuse it, else "".
std::string scene_error(const Sandbox& box, const std::string& scene) {
  return test::file_build_error(box.write("scene.toml", scene).string());
}

// A four-DOF chain: M diagonal, K tridiagonal (free end), written by rows and as files.
const std::string kMassRows = "[[1.0, 0, 0, 0], [0, 2.0, 0, 0], [0, 0, 1.5, 0], [0, 0, 0, 1.0]]";
const std::string kStiffnessRows =
    "[[2.0, -1.0, 0, 0], [-1.0, 2.0, -1.0, 0], [0, -1.0, 2.0, -1.0], [0, 0, -1.0, 1.0]]";
const std::string kMassFile =  // general storage
    "%%MatrixMarket matrix coordinate real general\n"
    "% a comment\n"
    "4 4 4\n1 1 1.0\n2 2 2.0\n3 3 1.5\n4 4 1.0\n";
const std::string kStiffnessFile =  // symmetric storage: the lower triangle only
    "%%MatrixMarket matrix coordinate real symmetric\n"
    "4 4 7\n1 1 2.0\n2 1 -1.0\n2 2 2.0\n3 2 -1.0\n3 3 2.0\n4 3 -1.0\n4 4 1.0\n";

const std::string kSolve = R"(
[solve]
t_end = 2.0
output_step = 0.25
rtol = 1e-8
atol = 1e-10
)";

/// The chain from files: Rayleigh damping, one constraint block of two rows (u1 = 0.5 t²,
/// u2 = u4) and a load pattern on u3 and u4 switched on at t = 0.25.
std::string files_scene(Sandbox& box) {
  box.write("M.mtx", kMassFile);
  box.write("K.mtx", kStiffnessFile);
  box.write("A.mtx",
            "%%MatrixMarket matrix coordinate real general\n2 4 3\n1 1 1.0\n2 2 1.0\n2 4 -1.0\n");
  box.write("g.mtx", "%%MatrixMarket matrix coordinate real general\n2 1 1\n1 1 0.5\n");
  box.write("f.mtx", "%%MatrixMarket matrix coordinate real general\n4 1 2\n3 1 1.0\n4 1 2.0\n");
  return R"([model]
type = "matrix"
mass = { file = "M.mtx" }
stiffness = { file = "K.mtx" }
damping = { rayleigh = [0.1, 0.01] }
[[constraint_block]]
file = "A.mtx"
name = "blk"
value = { file = "g.mtx" }
scale = { type = "polynomial", coefficients = [0.0, 0.0, 1.0] }
[[load]]
pattern = { file = "f.mtx" }
value = { type = "step", amplitude = 1.0, start = 0.25 }
)" + kSolve;
}

/// The same model written inline.
const std::string kInlineScene = R"([model]
type = "matrix"
dofs = ["u1", "u2", "u3", "u4"]
mass = )" + kMassRows + R"(
stiffness = )" + kStiffnessRows + R"(
damping = { rayleigh = [0.1, 0.01] }
[[constraint]]
name = "blk1"
terms = { u1 = 1.0 }
value = { type = "polynomial", coefficients = [0.0, 0.0, 0.5] }
[[constraint]]
name = "blk2"
terms = { u2 = 1.0, u4 = -1.0 }
[[load]]
dof = "u3"
value = { type = "step", amplitude = 1.0, start = 0.25 }
[[load]]
dof = "u4"
value = { type = "step", amplitude = 2.0, start = 0.25 }
)" + kSolve;

}  // namespace

TEST_CASE("matrix market: general and symmetric storage, comments, duplicates summed") {
  const auto general = parse_matrix_market(kMassFile);
  CHECK_FALSE(general.symmetric);
  CHECK(general.matrix.nonZeros() == 4);
  CHECK(general.matrix.coeff(1, 1) == 2.0);
  const auto sym = parse_matrix_market(kStiffnessFile);
  CHECK(sym.symmetric);
  // Expanded to both triangles: 4 diagonal + 2 x 3 off-diagonal entries.
  CHECK(sym.matrix.nonZeros() == 10);
  CHECK(sym.matrix.coeff(0, 1) == -1.0);
  CHECK(sym.matrix.coeff(1, 0) == -1.0);
  const auto dup = parse_matrix_market(
      "%%MatrixMarket matrix coordinate integer general\n\n2 2 3\n1 1 1\n1 1 2\n\n2 2 5\n");
  CHECK(dup.matrix.coeff(0, 0) == 3.0);
  CHECK(dup.matrix.coeff(1, 1) == 5.0);
  // Integers beyond 2^53 that doubles hold exactly, and exponent forms, are read.
  const auto big = parse_matrix_market(
      "%%MatrixMarket matrix coordinate integer general\n2 2 3\n1 1 9007199254740992\n"
      "2 2 -18014398509481984\n1 2 1e20\n");
  CHECK(big.matrix.coeff(0, 0) == 9007199254740992.0);
  CHECK(big.matrix.coeff(1, 1) == -18014398509481984.0);
  CHECK(big.matrix.coeff(0, 1) == 1e20);
  // Header words are case-insensitive (some writers capitalize them).
  CHECK(parse_matrix_market("%%MatrixMarket MATRIX Coordinate Real General\n1 1 1\n1 1 4\n")
            .matrix.coeff(0, 0) == 4.0);
  // A leading '+' is a sign, as C's readers and SciPy take it.
  CHECK(parse_matrix_market("%%MatrixMarket matrix coordinate real general\n+2 2 1\n+1 2 +4.5\n")
            .matrix.coeff(0, 1) == 4.5);
}

TEST_CASE("matrix market: arrays, as scipy.io.mmwrite writes numpy arrays") {
  // Column by column, one value per line; a symmetric array holds the lower triangle. Zeros are
  // not stored.
  const MarketMatrix column =
      parse_matrix_market("%%MatrixMarket matrix array real general\n%\n3 1\n0.0\n-2.5\n1e3\n");
  CHECK(column.matrix.rows() == 3);
  CHECK(column.matrix.cols() == 1);
  CHECK(column.matrix.nonZeros() == 2);
  CHECK(column.matrix.coeff(1, 0) == -2.5);
  CHECK(column.matrix.coeff(2, 0) == 1e3);
  const MarketMatrix general =
      parse_matrix_market("%%MatrixMarket matrix array real general\n2 3\n1\n2\n3\n4\n5\n6\n");
  CHECK(general.matrix.coeff(1, 0) == 2.0);  // column by column
  CHECK(general.matrix.coeff(0, 2) == 5.0);
  CHECK(general.matrix.coeff(1, 2) == 6.0);
  const MarketMatrix symmetric =
      parse_matrix_market("%%MatrixMarket matrix array real symmetric\n3 3\n4\n-1\n0\n5\n-2\n6\n");
  Eigen::MatrixXd expected(3, 3);
  expected << 4, -1, 0, -1, 5, -2, 0, -2, 6;
  CHECK(Eigen::MatrixXd(symmetric.matrix) == expected);
  CHECK(symmetric.matrix.nonZeros() == 7);
  const MarketMatrix integers =
      parse_matrix_market("%%MatrixMarket matrix array integer general\n2 1\n3\n-7\n");
  CHECK(integers.matrix.coeff(1, 0) == -7.0);
}

TEST_CASE("matrix market: malformed files are refused with their line") {
  const std::string general = "%%MatrixMarket matrix coordinate real general\n";
  struct Case {
    std::string text;
    int line;
    std::string says;
  };
  const Case cases[] = {
      {"", 0, "empty"},
      {"1 1 1\n1 1 1.0\n", 1, "not a Matrix Market header"},
      {"%%MatrixMarket matrix coordinate pattern general\n1 1 1\n1 1\n", 1, "pattern"},
      {"%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n", 1, "complex"},
      {"%%MatrixMarket matrix array real general\n2 1\n1.0\n", 3, "ends after 1 of the 2"},
      {"%%MatrixMarket matrix array real general\n2 1 2\n1.0\n2.0\n", 2, "two integers"},
      {"%%MatrixMarket matrix array real general\n1 1\n1 1 1.0\n", 3, "holds one value"},
      {"%%MatrixMarket matrix array real general\n1 1\n1.0\n2.0\n", 4, "more entries"},
      {"%%MatrixMarket matrix coordinate real hermitian\n1 1 1\n1 1 1.0\n", 1, "hermitian"},
      {"%%MatrixMarket matrix coordinate real skew-symmetric\n1 1 0\n", 1, "skew-symmetric"},
      {general, 1, "size line"},
      {general + "2 2\n", 2, "three integers"},
      {general + "0 2 0\n", 2, "not between 1"},
      {general + "2 2 -1\n", 2, "entry count -1 is negative"},
      {general + "2 2 5\n", 2, "ends after 0 of the 5"},
      {general + "2 x 1\n", 2,
       "the size line (rows cols entries, the first line after the "
       "header and comments) holds 'x', not a whole number"},
      // The size line left out: its first entry read in its place.
      {general + "1 1 1.0\n2 2 1.0\n", 2,
       "holds '1.0', not a whole number: is the size line "
       "missing, with an entry in its place?"},
      {"%%MatrixMarket matrix array real general\n1.5 2\n", 2, "(rows cols, the first line"},
      {general + "2 2 1\n3 1 1.0\n", 3, "outside the 2 x 2 matrix of the size line, line 2"},
      {general + "2 2 1\n1 0 1.0\n", 3, "outside the 2 x 2"},
      {general + "2 2 1\n1 1 nan\n", 3, "not finite"},
      {general + "2 2 1\n1 1 inf\n", 3, "not finite"},
      {general + "2 2 1\n1 1 1.0x\n", 3, "not a number"},
      {general + "2 2 1\n1 1 1e400\n", 3, "'1e400' is out of the double range"},
      {general + "2 2 1\n1 1 -1e-400\n", 3, "'-1e-400' is out of the double range"},
      {general + "2 2 1\n1 1 ++1\n", 3, "not a number"},
      {general + "2 2 1\n+-1 1 1\n", 3, "not an integer"},
      {"%%MatrixMarket matrix coordinate integer general\n2 2 1\n1 1 100.9\n", 3,
       "'100.9' is not an integer"},
      // Beyond 2^53 an integer may have no double: it used to be rounded silently.
      {"%%MatrixMarket matrix coordinate integer general\n2 2 1\n1 1 9007199254740993\n", 3,
       "the integer '9007199254740993' is beyond 2^53 and not held exactly by a double (it "
       "would be 9007199254740992); write the value meant, or the field 'real'"},
      {"%%MatrixMarket matrix array integer general\n1 1\n-00018014398509481985\n", 3,
       "(it would be 18014398509481984)"},
      {general + "2 2 1\n1 1\n", 3, "found 2 fields"},
      {general + "2 2 2\n1 1 1.0\n", 3, "ends after 1 of the 2"},
      {general + "2 2 1\n1 1 1.0\n2 2 1.0\n", 4, "more entries"},
      {"%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1.0\n", 3, "above the diag"},
      {"%%MatrixMarket matrix coordinate real symmetric\n2 3 0\n", 2, "must be square"},
      {general + "1 1 2\n1 1 1e308\n1 1 1e308\n", 0, "beyond the double range"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    // Not a structured binding: clang 14 cannot capture one in doctest's message lambda.
    const auto error = market_error(c.text);
    const std::string& what = error.second;
    CHECK(error.first == c.line);
    CHECK_MESSAGE(has(what, c.says), what);
  }
}

TEST_CASE("matrix market: a size line beyond the memory available is refused before allocating") {
  // A size line of another file, or a typo: 2·10⁹ columns took the process down while Eigen
  // filled its index arrays. 2^31 - 1 rows and columns need 34 GB of index arrays (8 bytes a row
  // and a column); where that much is available the case cannot be shown without using it.
  const auto available = condyn::available_memory_bytes();
  if (!available || *available > 3.0e10) {
    MESSAGE("not shown: this machine has the 34 GB available");
    return;
  }
  const auto error = market_error(
      "%%MatrixMarket matrix coordinate real general\n2147483647 2147483647 1\n1 1 1.0\n");
  CHECK(error.first == 2);
  CHECK_MESSAGE(has(error.second, "needs 34.4 GB, more than the"), error.second);
  CHECK_MESSAGE(has(error.second, "is the size line right?"), error.second);
}

TEST_CASE("matrix market: a model matrix's size line is refused when its DOFs could not be run") {
  // 10⁸ DOFs with one entry: the matrix takes 1.6 GB, but a run of 10⁸ DOFs holds at least
  // IDA's vectors (30 of 2·10⁸ doubles, 48 GB) and the Newton matrix: before this check the DOF
  // names and vectors were built until memory ran out, with a message naming no file.
  const auto available = condyn::available_memory_bytes();
  if (!available || *available > 4.0e10) {
    MESSAGE("not shown: this machine has the 48 GB available");
    return;
  }
  const std::string text =
      "%%MatrixMarket matrix coordinate real symmetric\n100000000 100000000 1\n1 1 1.0\n";
  MarketExpectation model;
  model.rows_are_dofs = true;
  const auto error = market_error(text, model);
  CHECK(error.first == 2);
  CHECK_MESSAGE(has(error.second,
                    "holding it and integrating a model of 100000000 DOFs needs at "
                    "least "),
                error.second);
  CHECK_MESSAGE(has(error.second, "is the size line right?"), error.second);
}

TEST_CASE(
    "matrix market: a constraint block with fewer entries than rows is refused at its size "
    "line") {
  // 2·10⁹ rows and 2 entries fit the memory estimate of a large machine and ran for minutes
  // (docs/benchmarks.md).
  const std::string text =
      "%%MatrixMarket matrix coordinate real general\n2000000000 3 2\n"
      "1 1 1.0\n2 2 1.0\n";
  try {
    MarketExpectation block;
    block.rows_need_entries = true;
    (void)parse_matrix_market(text, block);
    FAIL("accepted");
  } catch (const MatrixMarketError& e) {
    CHECK(e.line() == 2);
    CHECK(has(e.what(), "declares 2000000000 rows but 2 entries, so some row has none"));
  }
  // M, C and K may have empty rows (massless, unsprung DOFs): not refused there.
  CHECK(parse_matrix_market("%%MatrixMarket matrix coordinate real general\n3 3 1\n1 1 1.0\n")
            .matrix.rows() == 3);
}

TEST_CASE("matrix market: a byte order mark, lone CR endings, messages show no control bytes") {
  const std::string body = "3 3 3\n1 1 2\n2 2 2\n3 3 2\n";
  const std::string header = "%%MatrixMarket matrix coordinate real general\n";
  // A BOM before the header (a Windows editor's), and a file with lone CR line ends, read as
  // the plain file (the header was 'not a Matrix Market header', the whole file one line).
  CHECK(parse_matrix_market("\xEF\xBB\xBF" + header + body).matrix.nonZeros() == 3);
  std::string mac = header + body;
  std::replace(mac.begin(), mac.end(), '\n', '\r');
  CHECK(parse_matrix_market(mac).matrix.coeff(2, 2) == 2.0);
  std::string crlf;
  for (char c : header + body) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  CHECK(parse_matrix_market(crlf).matrix.coeff(1, 1) == 2.0);
  try {  // a lone-CR file counts its lines too
    std::string bad = header + "3 3 1\n1 1 x\n";
    std::replace(bad.begin(), bad.end(), '\n', '\r');
    (void)parse_matrix_market(bad);
    FAIL("accepted");
  } catch (const MatrixMarketError& e) {
    CHECK(e.line() == 3);
  }
  // A NUL cut the message off and an escape sequence reached the terminal: shown as '?'.
  CHECK_THROWS_WITH_AS(
      (void)parse_matrix_market(header + "1 1 1\n1 1 2" + std::string(1, '\0') + "x\n"),
      "the value '2?x' is not a number", MatrixMarketError);
  CHECK_THROWS_WITH_AS((void)parse_matrix_market(header + "1 1 1\n1 1 2\x1b[2J\n"),
                       "the value '2?[2J' is not a number", MatrixMarketError);
  // An integer beyond 2^63 - 1 is one, out of range.
  CHECK_THROWS_WITH_AS((void)parse_matrix_market(header + "1 1 99999999999999999999\n"),
                       "the entry count '99999999999999999999' is out of range (beyond 2^63 - 1)",
                       MatrixMarketError);
}

TEST_CASE("matrix market: a size the caller knows is checked at the size line") {
  // 3·10⁸ for 3 (the model's size known from M) was allocated in full, gigabytes, before the
  // size was compared with M's (docs/benchmarks.md).
  MarketExpectation three;
  three.rows = three.cols = 3;
  three.because = "M.mtx is 3 x 3";
  const std::string text =
      "%%MatrixMarket matrix coordinate real symmetric\n300000000 300000000 1\n1 1 2.0\n";
  try {
    (void)parse_matrix_market(text, three);
    FAIL("accepted");
  } catch (const MatrixMarketError& e) {
    CHECK(e.line() == 2);
    CHECK(std::string(e.what()) ==
          "the size line declares 300000000 x 300000000 but M.mtx is 3 x 3: is the size line "
          "right?");
  }
  CHECK(parse_matrix_market("%%MatrixMarket matrix coordinate real symmetric\n3 3 1\n1 1 2.0\n",
                            three)
            .matrix.rows() == 3);
  // Only what is known is checked: a load pattern's columns (1), a block's columns (n).
  MarketExpectation column;
  column.cols = 1;
  column.because = "a load pattern is one column";
  CHECK_THROWS_WITH_AS(
      (void)parse_matrix_market("%%MatrixMarket matrix coordinate real general\n3 2 1\n1 1 1\n",
                                column),
      "the size line declares 3 x 2 but a load pattern is one column: is the size line right?",
      MatrixMarketError);
}

TEST_CASE("matrix market: a file that cannot be opened, or is no regular file") {
  CHECK_THROWS_AS((void)read_matrix_market("/nonexistent/K.mtx"), MatrixMarketError);
  // A device is read forever: refused before reading.
  CHECK_THROWS_WITH_AS((void)read_matrix_market("/dev/zero"), "is not a regular file",
                       MatrixMarketError);
}

TEST_CASE("matrix model from files: DOFs u1..un, sparse matrices as the files say") {
  Sandbox box;
  const Model model = build_model(parse_scene_file(box.write("s.toml", files_scene(box)).string()));
  REQUIRE(model.dofs() == 4);
  CHECK(model.dof_names.front() == "u1");
  CHECK(model.dof_names.back() == "u4");
  CHECK(model.K->nonZeros() == 10);
  CHECK(model.K->coeff(3, 2) == -1.0);
  // C = a0 M + a1 K, entry by entry (one product and one sum each: exact to 1 ulp; compared
  // against the same expression, so exactly equal).
  const Eigen::SparseMatrix<double> expected = 0.1 * model.M + 0.01 * *model.K;
  CHECK(Eigen::MatrixXd(model.C) == Eigen::MatrixXd(expected));
  // The block's rows, named PREFIX1..PREFIXm, and its right-hand side 0.5 t² and 0.
  REQUIRE(model.constraint_count() == 2);
  CHECK(model.constraints[0].name == "blk1");
  CHECK(model.constraints[1].name == "blk2");
  CHECK(model.constraints[0].value.value(2.0) == 2.0);
  CHECK(model.constraints[1].value.is_zero());
  CHECK(model.A.coeff(1, 3) == -1.0);
  // The pattern: one load, a sparse vector times the time function.
  REQUIRE(model.loads.size() == 1);
  CHECK(model.loads[0].pattern.nonZeros() == 2);
  CHECK(model.applied_forces(1.0)[3] == 2.0);
  CHECK(model.applied_forces(0.0)[3] == 0.0);
}

TEST_CASE("release_model_input frees what the model holds, and keeps what a run still reads") {
  Sandbox box;
  SceneSpec spec = parse_scene_file(box.write("s.toml", files_scene(box)).string());
  const Model model = build_model(spec);
  REQUIRE(spec.model.stiffness_file.matrix.nonZeros() == 10);
  const SolveSpec solve = spec.solve;
  const std::vector<Quantity> quantities = spec.output.quantities;
  release_model_input(spec);
  // Freed, not only emptied: Eigen 3.4 keeps a sparse matrix's storage when an empty one is
  // assigned to it.
  CHECK(spec.model.stiffness_file.matrix.data().allocatedSize() == 0);
  CHECK(spec.model.mass_file.matrix.data().allocatedSize() == 0);
  CHECK(spec.loads.empty());
  CHECK(spec.constraint_blocks.empty());
  // What the run reads after building stays; the model keeps its own copy and still runs.
  CHECK(spec.file == box.path("s.toml").string());
  CHECK(spec.solve.t_end == solve.t_end);
  CHECK(spec.solve.scheme == solve.scheme);
  CHECK(spec.output.quantities == quantities);
  CHECK(model.K->nonZeros() == 10);
  CHECK(test::solved(model, spec.solve).ok());
}

TEST_CASE("matrix model from files: dofs may be given, and inline rows mix with files") {
  Sandbox box;
  box.write("K.mtx", kStiffnessFile);
  const std::string scene = R"([model]
type = "matrix"
dofs = ["a", "b", "c", "d"]
mass = )" + kMassRows + R"(
stiffness = { file = "K.mtx" }
[[load]]
dof = "d"
value = 1.0
)" + kSolve;
  const Model model = build_model(parse_scene_file(box.write("s.toml", scene).string()));
  CHECK(model.dof_names[2] == "c");
  CHECK(model.K->coeff(2, 1) == -1.0);
}

TEST_CASE("matrix model from files: paths are relative to the scene file's folder") {
  Sandbox box;
  std::filesystem::create_directories(box.path("case/mats"));
  box.write("case/mats/M.mtx", kMassFile);
  box.write("case/mats/K.mtx", kStiffnessFile);
  const std::string scene = R"([model]
type = "matrix"
mass = { file = "mats/M.mtx" }
stiffness = { file = "mats/K.mtx" }
)" + kSolve;
  // The test's working directory is not the sandbox: only the scene's folder finds the files.
  const Model model = build_model(parse_scene_file(box.write("case/s.toml", scene).string()));
  CHECK(model.dofs() == 4);
}

TEST_CASE("matrix model from files: bad files name the scene, the key, the file and its line") {
  Sandbox box;
  box.write("M.mtx", kMassFile);
  const auto with_stiffness = [](const std::string& file) {
    return R"([model]
type = "matrix"
mass = { file = "M.mtx" }
stiffness = { file = ")" +
           file + R"(" }
)" + kSolve;
  };
  const std::string scene = box.path("scene.toml").string();

  std::string e = scene_error(box, with_stiffness("missing.mtx"));
  CHECK(has(e, scene + ":4: model.stiffness.file: "));
  CHECK(has(e, box.path("missing.mtx").string() + ": cannot open the file"));

  box.write("bad.mtx", "%%MatrixMarket matrix coordinate real general\n4 4 1\n5 1 1.0\n");
  e = scene_error(box, with_stiffness("bad.mtx"));
  CHECK(has(e, "model.stiffness.file: " + box.path("bad.mtx").string() + ":3: the index (5, 1)"));

  box.write("nan.mtx", "%%MatrixMarket matrix coordinate real general\n4 4 1\n1 1 NaN\n");
  CHECK(has(scene_error(box, with_stiffness("nan.mtx")), "nan.mtx:3: the value 'NaN' is not"));

  box.write("header.mtx", "%%MatrixMarket matrix coordinate pattern general\n4 4 1\n1 1\n");
  CHECK(has(scene_error(box, with_stiffness("header.mtx")), "header.mtx:1: field 'pattern'"));

  box.write("three.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 1\n1 1 1.0\n");
  CHECK(has(scene_error(box, with_stiffness("three.mtx")),
            "model.stiffness.file: " + box.path("three.mtx").string() +
                ":2: the size line declares 3 x 3 but M.mtx (model.mass, line 3) is 4 x 4: mass, "
                "stiffness and damping must have one size; is one of the two files the wrong "
                "one, or its size line wrong?"));
  box.write("wide.mtx", "%%MatrixMarket matrix coordinate real general\n4 5 1\n1 1 1.0\n");
  const std::string wide = R"([model]
type = "matrix"
mass = { file = "wide.mtx" }
stiffness = { file = "three.mtx" }
)" + kSolve;
  CHECK(
      has(scene_error(box, wide), "model.mass.file: wide.mtx is 4 x 5: a square matrix is needed"));

  // General storage that is not symmetric: refused (M, K and C must be), sparse check.
  box.write("asym.mtx",
            "%%MatrixMarket matrix coordinate real general\n4 4 5\n1 1 1\n2 2 1\n3 3 1\n4 4 1\n"
            "2 1 0.5\n");
  CHECK(has(scene_error(box, with_stiffness("asym.mtx")),
            "asym.mtx is not symmetric: entry (2,1) = 0.5 but (1,2) = 0"));

  // Symmetric but indefinite: the eigenvalue check of small matrices.
  box.write("indef.mtx",
            "%%MatrixMarket matrix coordinate real symmetric\n4 4 4\n1 1 1\n2 2 -1\n3 3 1\n4 4 "
            "1\n");
  CHECK(has(scene_error(box, with_stiffness("indef.mtx")),
            "model.stiffness.file: indef.mtx is not positive semi-definite"));

  // Without files, dofs stays required.
  CHECK(has(scene_error(
                box, "[model]\ntype = \"matrix\"\nmass = [[1.0]]\nstiffness = [[1.0]]\n" + kSolve),
            "model.dofs: missing required key"));
}

TEST_CASE("matrix model from files: large matrices are checked without a dense copy") {
  // 600 DOFs, above the size up to which the dense eigenvalue check runs (kDensePsdCheck = 500),
  // where Eigen's sparse LDLt decides; 12,000, above kCholmodAbove (10,000), where CHOLMOD's
  // supernodal Cholesky does.
  for (const int n : {600, 12000}) {
    CAPTURE(n);
    std::string diag = "%%MatrixMarket matrix coordinate real symmetric\n" + std::to_string(n) +
                       " " + std::to_string(n) + " " + std::to_string(n) + "\n";
    std::string bad_minor = "%%MatrixMarket matrix coordinate real symmetric\n" +
                            std::to_string(n) + " " + std::to_string(n) + " " +
                            std::to_string(n + 1) + "\n";
    std::string negative = diag;
    for (int i = 1; i <= n; ++i) {
      diag += std::to_string(i) + " " + std::to_string(i) + " 1.0\n";
      bad_minor += std::to_string(i) + " " + std::to_string(i) + " 1.0\n";
      negative += std::to_string(i) + " " + std::to_string(i) + (i == 7 ? " -1.0\n" : " 1.0\n");
    }
    bad_minor += "2 1 3.0\n";  // [[1, 3], [3, 1]] has eigenvalue -2
    Sandbox box;
    box.write("I.mtx", diag);
    box.write("neg.mtx", negative);
    box.write("minor.mtx", bad_minor);
    const auto scene = [](const std::string& k) {
      return "[model]\ntype = \"matrix\"\nmass = { file = \"I.mtx\" }\nstiffness = { file = \"" +
             k + "\" }\n" + kSolve;
    };
    CHECK(scene_error(box, scene("I.mtx")).empty());
    CHECK(has(scene_error(box, scene("neg.mtx")), "diagonal entry (7,7) = -1 < 0"));
    CHECK(has(scene_error(box, scene("minor.mtx")), "|entry (2,1)| = 3 exceeds"));
    // Tridiagonal, diagonal 1 and off-diagonal 0.9: every 2 x 2 minor is positive (accepted
    // before), but the eigenvalues 1 + 1.8 cos(k pi / (n + 1)) go down to about -0.8. The sparse
    // factorization refuses it; the same pattern with 0.5 (eigenvalues >= 1 - cos(pi/(n+1)) > 0)
    // passes, and so does the free-free spring chain (diagonal 1, 2, ..., 2, 1 and -1 beside it:
    // positive semi-definite with the rigid motion as an exact zero eigenvalue).
    const auto tridiagonal = [n](double end, double middle, double off) {
      std::string t = "%%MatrixMarket matrix coordinate real symmetric\n" + std::to_string(n) +
                      " " + std::to_string(n) + " " + std::to_string(2 * n - 1) + "\n";
      for (int i = 1; i <= n; ++i) {
        t += std::to_string(i) + " " + std::to_string(i) + " " +
             std::to_string(i == 1 || i == n ? end : middle) + "\n";
        if (i < n)
          t += std::to_string(i + 1) + " " + std::to_string(i) + " " + std::to_string(off) + "\n";
      }
      return t;
    };
    box.write("tri09.mtx", tridiagonal(1.0, 1.0, 0.9));
    box.write("tri05.mtx", tridiagonal(1.0, 1.0, 0.5));
    box.write("chain.mtx", tridiagonal(1.0, 2.0, -1.0));
    const std::string refusal = scene_error(box, scene("tri09.mtx"));
    CHECK(has(refusal, "tri09.mtx is not positive semi-definite (stiffness): a sparse "));
    CHECK(has(refusal, n < 10000 ? "negative pivot" : "Cholesky factorization of it"));
    CHECK(has(refusal, "eigenvalue below -1e-08 of its largest diagonal entry"));
    CHECK(scene_error(box, scene("tri05.mtx")).empty());
    CHECK(scene_error(box, scene("chain.mtx")).empty());
  }
}

TEST_CASE("rayleigh damping: truss models too, and refusals") {
  const std::string truss = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [1.0, 2.0]
supports = [1]
members = [{ nodes = [1, 2], EA = 10.0 }]
damping = { rayleigh = [0.5, 0.02] }
[[constraint]]
terms = { uy2 = 1.0 }
)" + kSolve;
  const Model model = build_model(parse_scene_text(truss, "t.toml"));
  REQUIRE(model.has_damping());
  const Eigen::SparseMatrix<double> expected = 0.5 * model.M + 0.02 * *model.K;
  CHECK(Eigen::MatrixXd(model.C) == Eigen::MatrixXd(expected));
  const auto error = [](const std::string& text) { return test::build_error(text, "t.toml"); };
  CHECK(has(error(condyn::test::replace(truss, "[0.5, 0.02]", "[-0.5, 0.02]")),
            "t.toml:7: model.damping.rayleigh[1]: must be >= 0"));
  CHECK(has(error(condyn::test::replace(truss, "[0.5, 0.02]", "[0.5]")),
            "model.damping.rayleigh: expected [a0, a1]"));
  CHECK(has(error(condyn::test::replace(truss, "rayleigh =", "rayleig =")), "model.damping"));
  // A file beside rayleigh: the pair is the mistake, not 'file: unknown key'.
  CHECK(has(error(condyn::test::replace(truss, "rayleigh =", "file = \"C.mtx\", rayleigh =")),
            "model.damping.file: give either a damping matrix (file) or rayleigh or modal "
            "damping, not both"));
  // A file alone on a truss: there is no pair, the model type is the mistake.
  CHECK(
      has(error(condyn::test::replace(truss, "{ rayleigh = [0.5, 0.02] }", "{ file = \"C.mtx\" }")),
          "model.damping.file: a damping matrix from a file is for matrix models (type = "
          "\"matrix\"): give rayleigh or modal damping"));
  // Beside a rigid member (issue 44): a0 M and dashpots on the bars
  // (tests/models/test_member_dampers.cpp), no longer refused.
  CHECK(error(condyn::test::replace(truss, "EA = 10.0", "rigid = true")).empty());
}

TEST_CASE("constraint blocks: default names, values, and refusals") {
  Sandbox box;
  box.write("M.mtx", kMassFile);
  box.write("K.mtx", kStiffnessFile);
  box.write("A1.mtx", "%%MatrixMarket matrix coordinate real general\n1 4 1\n1 1 1.0\n");
  box.write("A2.mtx", "%%MatrixMarket matrix coordinate real general\n1 4 1\n1 2 1.0\n");
  const std::string base = R"([model]
type = "matrix"
mass = { file = "M.mtx" }
stiffness = { file = "K.mtx" }
[[constraint_block]]
file = "A1.mtx"
[[constraint_block]]
file = "A2.mtx"
)" + kSolve;
  const Model model = build_model(parse_scene_file(box.write("s.toml", base).string()));
  REQUIRE(model.constraint_count() == 2);
  CHECK(model.constraints[0].name == "block1_1");
  CHECK(model.constraints[1].name == "block2_1");
  CHECK(model.constraints[1].value.is_zero());

  box.write("wide.mtx", "%%MatrixMarket matrix coordinate real general\n1 5 1\n1 1 1.0\n");
  CHECK(has(scene_error(box, condyn::test::replace(base, "A2.mtx", "wide.mtx")),
            "wide.mtx:2: the size line declares 1 x 5 but a constraint block needs one column "
            "per DOF (4): is the size line right?"));
  box.write("empty.mtx", "%%MatrixMarket matrix coordinate real general\n2 4 1\n1 1 1.0\n");
  CHECK(has(scene_error(box, condyn::test::replace(base, "A2.mtx", "empty.mtx")),
            "empty.mtx:2: the size line declares 2 rows but 1 entries, so some row has none"));
  box.write("empty.mtx",
            "%%MatrixMarket matrix coordinate real general\n2 4 2\n1 1 1.0\n1 2 1.0\n");
  CHECK(has(scene_error(box, condyn::test::replace(base, "A2.mtx", "empty.mtx")),
            "row 2 has no nonzero entry: constraint 'block2_2' constrains nothing"));
  box.write("g2.mtx", "%%MatrixMarket matrix coordinate real general\n2 1 0\n");
  CHECK(has(scene_error(box, condyn::test::replace(base, "file = \"A2.mtx\"",
                                                   "file = \"A2.mtx\"\nvalue = { file = "
                                                   "\"g2.mtx\" }")),
            "g2.mtx:2: the size line declares 2 x 1 but the right-hand side of A2.mtx (1 rows) "
            "must be 1 x 1"));
  CHECK(has(scene_error(box, condyn::test::replace(base, "file = \"A2.mtx\"",
                                                   "file = \"A2.mtx\"\nname = \"block1_\"")),
            "duplicate constraint block name 'block1_'"));
  // A block's row names are columns like any constraint's.
  CHECK(has(scene_error(box, condyn::test::replace(base, "[[constraint_block]]",
                                                   "[[constraint]]\nname = \"block2_1\"\nterms = "
                                                   "{ u3 = 1.0 }\n[[constraint_block]]")),
            "constraint_block[2]: row 1 of constraint_block[2], 'block2_1' (its default prefix "
            "'block2_' and the row number, line 10) gives the column 'lambda_block2_1', which "
            "is already the multiplier column of constraint[1] 'block2_1' (line 6)"));
  // An unnamed constraint's default name against a named block's row: both named as such.
  const std::string default_clash = scene_error(
      box,
      condyn::test::replace(
          condyn::test::replace(base, "file = \"A2.mtx\"", "file = \"A2.mtx\"\nname = \"c\""),
          "[[constraint_block]]", "[[constraint]]\nterms = { u3 = 1.0 }\n[[constraint_block]]"));
  CHECK(has(default_clash,
            "constraint_block[2].name: row 1 of constraint_block[2], 'c1' (its name 'c' and the "
            "row number, line"));
  CHECK(has(default_clash,
            "already the multiplier column of constraint[1] 'c1' (its default name, line"));
  CHECK(has(scene_error(box, condyn::test::replace(base, "file = \"A2.mtx\"",
                                                   "file = \"A2.mtx\"\nscale = { type = \"step\", "
                                                   "start = 0.5 }")),
            "constraint_block[2].scale: a step at t = 0.5"));
  // After t_end (2) the run never reaches it: accepted with a warning.
  BuildReport report;
  const Model late =
      build_model(parse_scene_file(
                      box.write("late.toml", condyn::test::replace(base, "file = \"A2.mtx\"",
                                                                   "file = \"A2.mtx\"\nscale = "
                                                                   "[{ type = \"step\", start "
                                                                   "= 2.5 }, { type = \"step\" }]"))
                          .string()),
                  report);
  REQUIRE(report.warnings.size() == 1);
  CHECK(report.warnings[0] ==
        "constraint_block[2].scale: the step at t = 2.5 starts after t_end "
        "= 2 and has no effect on this run");
}

TEST_CASE("load patterns: size checked, dof or pattern") {
  Sandbox box;
  box.write("M.mtx", kMassFile);
  box.write("K.mtx", kStiffnessFile);
  box.write("f3.mtx", "%%MatrixMarket matrix coordinate real general\n3 1 1\n1 1 1.0\n");
  const std::string base = R"([model]
type = "matrix"
mass = { file = "M.mtx" }
stiffness = { file = "K.mtx" }
[[load]]
pattern = { file = "f3.mtx" }
value = 1.0
)" + kSolve;
  CHECK(has(scene_error(box, base),
            "f3.mtx:2: the size line declares 3 x 1 but a load pattern is n x 1 (n = 4 DOFs): is "
            "the size line right?"));
  CHECK(has(scene_error(box, condyn::test::replace(base, "value = 1.0", "dof = \"u1\"\nvalue = 1")),
            "load[1].pattern: give either dof or pattern, not both"));
  // A pattern of no nonzero entry applies no force: said (it ran unloaded without a word).
  box.write("f0.mtx", "%%MatrixMarket matrix coordinate real general\n4 1 1\n2 1 0.0\n");
  const auto empty = test::built(parse_scene_file(
      box.write("s.toml", condyn::test::replace(base, "f3.mtx", "f0.mtx")).string()));
  REQUIRE(empty.report.warnings.size() == 1);
  CHECK(empty.report.warnings[0] ==
        "load[1].pattern.file: f0.mtx has no nonzero entry: this load applies no force");
  CHECK(empty.model.loads.empty());
}

TEST_CASE("matrix model from files runs exactly as the same model written inline") {
  Sandbox box;
  const auto from_files =
      test::built(parse_scene_file(box.write("files.toml", files_scene(box)).string()));
  const auto inline_rows = test::built(parse_scene_text(kInlineScene, "inline.toml"));
  REQUIRE(from_files.model.dof_names == inline_rows.model.dof_names);
  // Same matrices, same rows, same loads term by term: the integrator sees identical numbers,
  // so the trajectories agree bit for bit.
  CHECK(Eigen::MatrixXd(from_files.model.M) == Eigen::MatrixXd(inline_rows.model.M));
  CHECK(Eigen::MatrixXd(*from_files.model.K) == Eigen::MatrixXd(*inline_rows.model.K));
  CHECK(Eigen::MatrixXd(from_files.model.C) == Eigen::MatrixXd(inline_rows.model.C));
  CHECK(Eigen::MatrixXd(from_files.model.A) == Eigen::MatrixXd(inline_rows.model.A));
  for (const Scheme scheme : {Scheme::elimination, Scheme::ggl, Scheme::index1}) {
    CAPTURE(to_string(scheme));
    const auto a = test::solved(from_files.model, test::under(from_files.spec.solve, scheme));
    const auto b = test::solved(inline_rows.model, test::under(inline_rows.spec.solve, scheme));
    REQUIRE(a.trajectory.t == b.trajectory.t);
    CHECK(a.trajectory.u == b.trajectory.u);
    CHECK(a.trajectory.v == b.trajectory.v);
    CHECK(a.trajectory.multiplier == b.trajectory.multiplier);
    // The motion is not trivial: the load and the prescribed u1 = 0.5 t² move every DOF.
    CHECK(a.trajectory.u.col(a.trajectory.u.cols() - 1).cwiseAbs().minCoeff() > 0.1);
  }
}

}  // namespace test_matrix_market
