// The README's first example (issue 14): its scene is models/scenes/quickstart.toml word for word,
// and the output it shows is what the program prints and writes for that scene (numbers to
// 1e-6 relative, since the sanitizer build's compiler may round the last digits differently).
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_sandbox.hpp"

namespace test_cli_readme_example {

using condyn::test::Sandbox;
using condyn::test::slurp;

namespace {

std::string source(const std::string& path) {
  return slurp(std::string(CONDYN_SOURCE_DIR) + "/" + path);
}

/// The text between the README's first "```toml" line and the next "```" line.
std::string readme_toml_block(const std::string& readme) {
  const auto open = readme.find("```toml\n");
  REQUIRE(open != std::string::npos);
  const auto start = open + 8;
  const auto close = readme.find("```", start);
  REQUIRE(close != std::string::npos);
  return readme.substr(start, close - start);
}

/// The scene file without its leading comment block (the README introduces the scene in prose).
std::string without_leading_comments(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  bool body = false;
  while (std::getline(in, line)) {
    if (!body && (line.empty() || line[0] == '#')) continue;
    body = true;
    out += line + "\n";
  }
  return out;
}

std::vector<double> numbers(const std::string& csv_row) {
  std::vector<double> v;
  std::istringstream in(csv_row);
  std::string cell;
  while (std::getline(in, cell, ',')) v.push_back(std::stod(cell));
  return v;
}

/// The line of `text` that starts with `prefix` (after the README's four-space indent).
std::string line_starting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.compare(first, prefix.size(), prefix) == 0)
      return line.substr(first);
  }
  return "";
}

}  // namespace

TEST_CASE("README: the first scene is models/scenes/quickstart.toml, its output as shown") {
  const std::string readme = source("README.md");
  const std::string scene = source("models/scenes/quickstart.toml");
  CHECK(readme_toml_block(readme) == without_leading_comments(scene));

  Sandbox box;
  box.write("quickstart.toml", scene);
  const auto r = box.run("run quickstart.toml --out quickstart.csv");
  REQUIRE(r.code == 0);
  // The summary: the scheme auto chose and the step count the README quotes.
  const std::string shown = line_starting(readme, "elimination: reached t = 2.000000, ");
  const std::string printed = line_starting(r.out, "elimination: reached t = 2.000000, ");
  REQUIRE(!shown.empty());
  REQUIRE(!printed.empty());
  const auto steps = [](const std::string& s) { return std::stod(s.substr(s.find(", ") + 2)); };
  CAPTURE(printed);
  CHECK(std::abs(steps(printed) - steps(shown)) <= 0.1 * steps(shown));
  CHECK(r.out.find(line_starting(readme, "damping: Rayleigh damping C = a0 M + a1 K")) !=
        std::string::npos);

  // The CSV rows the README shows: header exact, numbers to 1e-6 relative (1e-12 absolute).
  const std::string csv = slurp(box.path("quickstart.csv"));
  const std::string header =
      "t,u1,u2,u3,reaction_u1,reaction_u2,reaction_u3,drift_position,"
      "drift_velocity";
  CHECK(csv.rfind(header + "\n", 0) == 0);
  for (const std::string t : {"0,", "0.5,"}) {
    const std::string in_readme = line_starting(readme.substr(readme.find(header)), t);
    const std::string in_csv = line_starting(csv, t);
    REQUIRE(!in_readme.empty());
    REQUIRE(!in_csv.empty());
    const auto a = numbers(in_readme);
    const auto b = numbers(in_csv);
    REQUIRE(a.size() == b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      CAPTURE(k);
      CHECK(std::abs(a[k] - b[k]) <= 1e-6 * std::abs(b[k]) + 1e-12);
    }
  }
}

}  // namespace test_cli_readme_example
