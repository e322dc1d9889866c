// OutputPlan on its own: what commit does when a stream fails after the files are complete.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "src/output/output_files.hpp"
#include "tests/cli_sandbox.hpp"

namespace test_output_files {

namespace fs = std::filesystem;
using condyn::OutputError;
using condyn::OutputPlan;
using condyn::test::Sandbox;
using condyn::test::slurp;

TEST_CASE("OutputPlan: a stream that fails at commit leaves every file as it was") {
  const Sandbox box;
  box.write("keep.csv", "old\n");
  REQUIRE(fs::is_character_file("/dev/full"));  // every write to it fails with ENOSPC
  {
    OutputPlan plan;
    const auto file = plan.add_output(box.path("keep.csv").string(), "--out");
    const auto full = plan.add_output("/dev/full", "--steps-out");
    plan.check();
    CHECK(!plan.is_stream(file));
    CHECK(plan.is_stream(full));
    plan.write(file, [](std::ostream& out) { out << "new\n"; });
    plan.write(full, [](std::ostream& out) { out << "drift\n"; });
    CHECK_THROWS_AS(plan.commit({file, full}), std::runtime_error);
  }
  CHECK(slurp(box.path("keep.csv")) == "old\n");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(box.path("."))) ++files;
  CHECK(files == 1);  // keep.csv alone: the temporary file went with the plan
}

TEST_CASE("OutputPlan: outputs added after a check are checked against the earlier ones") {
  const Sandbox box;
  OutputPlan plan;
  plan.add_input(box.write("scene.toml", "x = 1\n").string());
  (void)plan.add_output(box.path("a.csv").string(), "--out");
  plan.check();
  (void)plan.add_output(box.path("./a.csv").string(), "--steps-out");
  CHECK_THROWS_AS(plan.check(), OutputError);
  OutputPlan second;
  second.add_input(box.path("scene.toml").string());
  (void)second.add_output(box.path("sub/../scene.toml").string(), "--out");
  fs::create_directory(box.path("sub"));
  CHECK_THROWS_AS(second.check(), OutputError);
  CHECK(slurp(box.path("scene.toml")) == "x = 1\n");
}

}  // namespace test_output_files
