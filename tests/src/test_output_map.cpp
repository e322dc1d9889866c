// A model's OutputMap gives every writer its columns (dae/run/mapped_rows.hpp,
// src/output/output_columns.hpp): CSV and HDF5, whole and streamed, [output] dofs and points,
// [[check]] quantities, and the drift summary's worst joint. The model is a pendulum written as a
// truss (a unit mass on a rigid member of length 1 from a support at the origin) that revolves
// over the top; its map, written here, shows the bob's angle from the downward vertical
// (continued across ±π from the previous row), the rod's length, the angular velocity and
// acceleration, the rod's multiplier as its reaction, and the bob as a named point.

#include <doctest/doctest.h>
#include <hdf5.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "dae/run/mapped_rows.hpp"
#include "models/core/mechanism.hpp"
#include "models/core/output_map.hpp"
#include "models/scene/scene_parser.hpp"
#include "src/output/csv_output.hpp"
#include "src/output/csv_rows.hpp"
#include "src/output/hdf5_output.hpp"
#include "src/output/output_columns.hpp"
#include "src/output/row_writer.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/hdf5_read.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/studies/user_checks.hpp"

using namespace condyn;

namespace test_output_map {

using condyn::test::Dataset;
using condyn::test::read_doubles;
using condyn::test::read_strings;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

/// Released with the rod horizontal at 6 m/s upwards: at the top, 1 m higher, v² = 36 − 2 g =
/// 16.4 > 0, so it revolves, and its angle from the downward vertical crosses ±π once a turn.
const std::string kRevolving = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }]
gravity = [0.0, -9.81]
[initial]
velocity = { uy2 = 6.0 }
[solve]
t_end = 3.0
output_step = 0.05
scheme = "ggl"
rtol = 1e-8
atol = 1e-10
[output]
quantities = ["displacement", "velocity", "acceleration", "reaction", "multiplier", "drift"]
)";

/// The bob at node 2 (DOFs ux2, uy2 at 2, 3; node 2 starts at x = 1).
class PendulumMap final : public OutputMap {
 public:
  explicit PendulumMap(int rod_row) : rod_row_(rod_row) {}

  [[nodiscard]] const std::vector<std::string>& names(Quantity q) const override {
    switch (q) {
      case Quantity::displacement:
        return displacement_;
      case Quantity::velocity:
        return velocity_;
      case Quantity::acceleration:
        return acceleration_;
      case Quantity::reaction:
        return reaction_;
      default:
        return none_;
    }
  }
  void displacement(double /*t*/, const Vector& u, const Vector& previous,
                    Vector& out) const override {
    const double x = 1.0 + u[2], y = u[3];
    double angle = std::atan2(x, -y);
    if (previous.size() > 0) angle = previous[0] + std::remainder(angle - previous[0], 2 * kPi);
    out << angle, std::hypot(x, y);
  }
  void velocity(double /*t*/, const Vector& u, const Vector& v, Vector& out) const override {
    const double x = 1.0 + u[2], y = u[3];
    out << (x * v[3] - y * v[2]) / (x * x + y * y);
  }
  void acceleration(double /*t*/, const Vector& u, const Vector& /*v*/, const Vector& a,
                    Vector& out) const override {
    const double x = 1.0 + u[2], y = u[3];
    out << (x * a[3] - y * a[2]) / (x * x + y * y);
  }
  void reaction(double /*t*/, const Vector& /*u*/, const Vector& lambda,
                Vector& out) const override {
    out << lambda[rod_row_];
  }
  [[nodiscard]] std::optional<int> point(std::string_view name) const override {
    return name == "bob.P" ? std::optional<int>(0) : std::nullopt;
  }
  void point_position(int /*index*/, const Vector& u, Eigen::Ref<Vector> out) const override {
    out << 1.0 + u[2], u[3];
  }
  [[nodiscard]] int dimension() const override { return 2; }

 private:
  int rod_row_;
  std::vector<std::string> displacement_{"bob.angle", "bob.r"}, velocity_{"bob.omega"},
      acceleration_{"bob.alpha"}, reaction_{"rod.f"}, none_;
};

/// The revolving pendulum built, with its map, run once (whole trajectory, model coordinates).
struct Revolving {
  test::BuiltScene scene = test::built(parse_scene_text(kRevolving, "revolving.toml"));
  int rod = -1;  ///< the rigid member's constraint row
  Trajectory traj;

  Revolving() {
    for (int i = 0; i < scene.model.constraint_count(); ++i) {
      if (scene.model.constraints[static_cast<std::size_t>(i)].name.rfind("fix_", 0) != 0) rod = i;
    }
    REQUIRE(rod >= 0);
    scene.model.outputs = std::make_shared<PendulumMap>(rod);
    scene.spec.output.points = {"bob.P"};
    traj = test::solved(scene.model, scene.spec.solve, hooks_for(scene.spec.output.quantities))
               .trajectory;
  }
  [[nodiscard]] std::string rod_name() const {
    return scene.model.constraints[static_cast<std::size_t>(rod)].name;
  }
  /// Row k of the trajectory as a streamed run hands it out.
  [[nodiscard]] TrajectoryRow row(Eigen::Index k) const {
    TrajectoryRow r;
    r.t = traj.t[static_cast<std::size_t>(k)];
    r.u = traj.u.col(k);
    r.v = traj.v.col(k);
    r.acceleration = traj.acceleration.col(k);
    r.reaction = traj.reaction.col(k);
    r.multiplier = traj.multiplier.col(k);
    r.drift_position = traj.drift_position[k];
    r.drift_velocity = traj.drift_velocity[k];
    return r;
  }
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) out.push_back(cell);
  return out;
}

/// The CSV's header and its rows as numbers.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  [[nodiscard]] std::size_t column(const std::string& name) const {
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (header[c] == name) return c;
    }
    FAIL("no column " << name);
    return 0;
  }
};

Table read_table(const std::string& text) {
  Table t;
  std::stringstream s(text);
  std::string line;
  std::getline(s, line);
  t.header = split(line);
  while (std::getline(s, line)) {
    std::vector<double> row;
    for (const auto& cell : split(line)) row.push_back(std::stod(cell));
    t.rows.push_back(row);
  }
  return t;
}

}  // namespace

TEST_CASE("a model's output map gives the CSV its columns, the same whole and streamed") {
  const Revolving p;
  const test::Sandbox box;
  const auto scene = box.write("revolving.toml", kRevolving);
  const OutputSpec& output = p.scene.spec.output;
  const RunAttributes run{"ggl", 1e-8, 1e-10, ""};
  RunOutputs whole(scene.string(), box.path("whole.csv").string(), output, "");
  whole.write(p.scene.model, run, p.traj);
  {
    const auto streamed =
        open_row_writer(box.path("streamed.csv").string(), false, p.scene.model, output);
    for (Eigen::Index k = 0; k < p.traj.u.cols(); ++k) streamed->row(p.row(k));
    streamed->finish(run);
  }
  const std::string text = test::slurp(box.path("whole.csv"));
  CHECK(text == test::slurp(box.path("streamed.csv")));
  const Table t = read_table(text);
  CHECK(t.header == std::vector<std::string>{"t", "bob.angle", "bob.r", "bob.omega", "bob.alpha",
                                             "rod.f", "lambda_fix_ux1", "lambda_fix_uy1",
                                             "lambda_" + p.rod_name(), "drift_position",
                                             "drift_velocity", "bob.P.x", "bob.P.y",
                                             "near_singular"});  // a rod: A depends on u
  REQUIRE(t.rows.size() == p.traj.t.size());
  // What the map computes from the row, bit for bit: its position, length and reaction.
  double lowest = 0.0, highest = 0.0;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const auto& r = t.rows[k];
    const auto col = static_cast<Eigen::Index>(k);
    const double x = 1.0 + p.traj.u(2, col), y = p.traj.u(3, col);
    CHECK(r[t.column("bob.P.x")] == x);
    CHECK(r[t.column("bob.P.y")] == y);
    CHECK(r[t.column("bob.r")] == std::hypot(x, y));
    CHECK(r[t.column("rod.f")] == r[t.column("lambda_" + p.rod_name())]);
    // The angle continues across ±π: consecutive rows a fraction of a turn apart (the bob turns
    // at most 6 rad/s, 0.3 rad a row), and it points at the bob to the roundoff of unwrapping
    // (an ulp or two of the angle and of 2π per turn).
    const double angle = r[t.column("bob.angle")];
    const double roundoff = 16 * kEps * std::max(1.0, std::abs(angle));
    CHECK(std::abs(std::sin(angle) - x / std::hypot(x, y)) <= roundoff);
    CHECK(std::abs(-std::cos(angle) - y / std::hypot(x, y)) <= roundoff);
    if (k > 0) CHECK(std::abs(angle - t.rows[k - 1][t.column("bob.angle")]) < 0.5);
    lowest = std::min(lowest, angle);
    highest = std::max(highest, angle);
  }
  CHECK(highest - lowest > 2 * kPi);  // it went round: a wrapped angle would stay in (−π, π]
}

TEST_CASE("[output] dofs selects a mechanism's columns of each quantity by their own names") {
  Revolving p;
  OutputSpec output = p.scene.spec.output;
  output.quantities = {Quantity::displacement, Quantity::velocity, Quantity::reaction};
  output.dofs = {"bob.angle", "rod.*"};
  output.points.clear();
  // The rod's A depends on u, and reactions are written: the rows end with their flag.
  CHECK(csv_header(output, OutputColumns(p.scene.model, output)) ==
        "t,bob.angle,rod.f,near_singular");
  output.dofs = {"bob.*"};
  output.points = {"bob.P"};
  CHECK(csv_header(output, OutputColumns(p.scene.model, output)) ==
        "t,bob.angle,bob.r,bob.omega,bob.P.x,bob.P.y,near_singular");
  // Without a map: per DOF, with the quantities' prefixes, as before.
  p.scene.model.outputs = nullptr;
  output.dofs = {"uy2"};
  output.points.clear();
  CHECK(csv_header(output, OutputColumns(p.scene.model, output)) ==
        "t,uy2,vel_uy2,reaction_uy2,near_singular");
  // Nothing the flag is about: no flag.
  output.quantities = {Quantity::displacement, Quantity::velocity};
  CHECK(csv_header(output, OutputColumns(p.scene.model, output)) == "t,uy2,vel_uy2");
}

TEST_CASE("a model's output map gives the HDF5 file its datasets and names, whole and streamed") {
  const Revolving p;
  const test::Sandbox box;
  const OutputSpec& output = p.scene.spec.output;
  const RunAttributes run{"ggl", 1e-8, 1e-10, ""};
  {
    std::ofstream out(box.path("whole.h5"), std::ios::binary);
    write_hdf5(out, p.scene.model, output, run, p.traj);
  }
  {
    const auto streamed =
        open_row_writer(box.path("streamed.h5").string(), true, p.scene.model, output);
    for (Eigen::Index k = 0; k < p.traj.u.cols(); ++k) streamed->row(p.row(k));
    streamed->finish(run);
  }
  const auto nt = static_cast<hsize_t>(p.traj.t.size());
  std::optional<Dataset> first_displacement;
  for (const char* name : {"whole.h5", "streamed.h5"}) {
    CAPTURE(name);
    const hid_t file = H5Fopen(box.path(name).c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    REQUIRE(file >= 0);
    CHECK(read_strings(file, "dof_names") == std::vector<std::string>{"bob.angle", "bob.r"});
    CHECK(read_strings(file, "velocity_names") == std::vector<std::string>{"bob.omega"});
    CHECK(read_strings(file, "acceleration_names") == std::vector<std::string>{"bob.alpha"});
    CHECK(read_strings(file, "reaction_names") == std::vector<std::string>{"rod.f"});
    CHECK(read_strings(file, "point_names") == std::vector<std::string>{"bob.P.x", "bob.P.y"});
    const Dataset u = read_doubles(file, "displacement");
    CHECK(u.dims == std::vector<hsize_t>{nt, 2});
    CHECK(read_doubles(file, "velocity").dims == std::vector<hsize_t>{nt, 1});
    CHECK(read_doubles(file, "reaction").dims == std::vector<hsize_t>{nt, 1});
    CHECK(read_doubles(file, "multiplier").dims ==
          std::vector<hsize_t>{nt, static_cast<hsize_t>(p.scene.model.constraint_count())});
    const Dataset points = read_doubles(file, "points");
    REQUIRE(points.dims == std::vector<hsize_t>{nt, 2});
    for (hsize_t k = 0; k < nt; ++k) {
      CHECK(points.values[2 * k] == 1.0 + p.traj.u(2, static_cast<Eigen::Index>(k)));
      CHECK(points.values[2 * k + 1] == p.traj.u(3, static_cast<Eigen::Index>(k)));
    }
    if (first_displacement) {
      CHECK(u.values == first_displacement->values);
    } else {
      first_displacement = u;
    }
    H5Fclose(file);
  }
}

TEST_CASE("[[check]] quantities name a mechanism's columns and its named points") {
  const Revolving p;
  const Model& model = p.scene.model;
  CHECK(find_column(model, "bob.omega")->quantity == Quantity::velocity);
  CHECK(find_column(model, "rod.f")->quantity == Quantity::reaction);
  CHECK(find_column(model, "bob.P.y")->point == 0);
  CHECK(find_column(model, "bob.P.y")->index == 1);
  CHECK_FALSE(find_column(model, "ux2"));      // the DOFs are not its columns
  CHECK_FALSE(find_column(model, "bob.P.z"));  // a planar point has no z
  const auto check = [](const std::string& quantity) {
    CheckSpec c;
    c.quantity = quantity;
    c.form = CheckSpec::Form::max_abs;
    c.bound = 1e9;
    c.where = {"check[1]", 1};
    return c;
  };
  CheckEvaluator evaluator(model, {check("bob.P.y"), check("rod.f"), check("bob.angle")}, "s.toml");
  CHECK(evaluator.quantities() ==
        std::vector<Quantity>{Quantity::displacement, Quantity::reaction});
  double max_y = 0.0, max_lambda = 0.0;
  for (Eigen::Index k = 0; k < p.traj.u.cols(); ++k) {
    evaluator.add(p.row(k));
    max_y = std::max(max_y, std::abs(p.traj.u(3, k)));
    max_lambda = std::max(max_lambda, std::abs(p.traj.multiplier(p.rod, k)));
  }
  const auto outcomes = evaluator.outcomes();
  CHECK(outcomes[0].computed == max_y);
  CHECK(outcomes[1].computed == max_lambda);
  CHECK(outcomes[2].computed > kPi);  // the continued angle, past a half turn
  CHECK_THROWS_WITH_AS(CheckEvaluator(model, {check("bob.omgea")}, "s.toml"),
                       doctest::Contains("the nearest: bob.omega"), SceneError);
}

TEST_CASE("the drift summary names a mechanism's worst joint, grouping rows by name") {
  Revolving p;
  Model& model = p.scene.model;
  model.constraints[0].name = "support.x";
  model.constraints[1].name = "support.y";
  model.constraints[static_cast<std::size_t>(p.rod)].name = "rod.length";
  // index1 lets the rod's length drift; the supports' rows hold exactly (u = 0 from rest).
  const SolveResult r = test::solved(model, test::under(p.scene.spec.solve, Scheme::index1));
  CHECK(r.summary.max_relative_drift_position > 0.0);
  CHECK(r.summary.worst_drift_joint == "rod");
  CHECK(r.summary.brief().find("(worst joint rod)") != std::string::npos);
  model.outputs = nullptr;  // not a mechanism: its rows are not joints'
  const SolveResult plain = test::solved(model, test::under(p.scene.spec.solve, Scheme::index1));
  CHECK(plain.summary.worst_drift_joint.empty());
  CHECK(plain.summary.brief().find("worst joint") == std::string::npos);
}

TEST_CASE("a body's rigid-body rows that drift most are named as the body's, not as a joint") {
  Revolving p;
  Model& model = p.scene.model;
  // The rod's row named as a body's unit-length row (natural coordinates name them so).
  model.constraints[static_cast<std::size_t>(p.rod)].name = "bob.rigid";
  const SolveResult r = test::solved(model, test::under(p.scene.spec.solve, Scheme::index1));
  CHECK(r.summary.max_relative_drift_position > 0.0);
  CHECK(r.summary.worst_drift_joint.empty());
  CHECK(r.summary.worst_drift_body == "bob");
  CHECK(r.summary.brief().find("(worst: the rigid-body rows of body bob)") != std::string::npos);
  CHECK(r.summary.brief().find("worst joint") == std::string::npos);
  // Which names are a body's rigid rows: "rigid" (2D), "rigid_" and two axes (3D), nothing else.
  CHECK(rigid_row_body("rod1.rigid") == "rod1");
  CHECK(rigid_row_body("link1.rigid_xz") == "link1");
  for (const char* joint_row : {"hinge.x", "rigid.x", "hinge.rigidity", "hinge.rigid_x", ".rigid"})
    CHECK(rigid_row_body(joint_row).empty());
}

TEST_CASE("[output] points is refused for a model without named points") {
  SceneSpec spec = parse_scene_text(kRevolving, "revolving.toml");
  spec.output.points = {"bob.P"};
  spec.output.points_lines = {7};
  CHECK_THROWS_WITH_AS((void)test::built(spec),
                       doctest::Contains("revolving.toml:7: output.points[1]: names a point of a "
                                         "mechanism"),
                       SceneError);
}

}  // namespace test_output_map
