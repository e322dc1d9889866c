// The user's documentation is complete inside the repository (issue 42, item 21): the README,
// docs/ (but for the developers' docs/contributing.md), the Python package and the CLI's own
// messages name no path outside it (the README sent users to ../shared/scene-format.md, which a
// clone does not have), and every relative link of the Markdown pages names a file in it.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace test_user_docs {

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = CONDYN_SOURCE_DIR;

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The files users read or whose text users see: pages, the Python package, the CLI's sources.
std::vector<fs::path> user_files() {
  std::vector<fs::path> out = {kRoot / "README.md"};
  for (const char* folder : {"docs", "python", "src"}) {
    for (const auto& entry : fs::recursive_directory_iterator(kRoot / folder)) {
      const fs::path& p = entry.path();
      const std::string ext = p.extension().string();
      if (!entry.is_regular_file() || p.filename() == "contributing.md") continue;
      if (ext == ".md" || ext == ".py" || ext == ".cpp" || ext == ".hpp") out.push_back(p);
    }
  }
  return out;
}

}  // namespace

TEST_CASE("the user documentation names no path outside the repository") {
  const std::vector<fs::path> files = user_files();
  REQUIRE(files.size() > 20);  // the README, the pages, the package and the CLI's sources
  for (const auto& file : files) {
    CAPTURE(file.string());
    const std::string text = text_of(file);
    CHECK(text.find("../shared") == std::string::npos);
    CHECK(text.find("/work/shared") == std::string::npos);
  }
}

TEST_CASE("every relative link of the Markdown pages names a file of the repository") {
  const std::regex link(R"(\]\(([^)#\s]+)(#[^)]*)?\))");
  int links = 0;
  for (const auto& file : user_files()) {
    if (file.extension() != ".md") continue;
    const std::string text = text_of(file);
    for (std::sregex_iterator it(text.begin(), text.end(), link), end; it != end; ++it) {
      const std::string target = (*it)[1].str();
      if (target.rfind("http", 0) == 0) continue;
      CAPTURE(file.string());
      CAPTURE(target);
      const fs::path resolved = (file.parent_path() / target).lexically_normal();
      CHECK(fs::exists(resolved));
      // Inside the repository: no climbing out of it.
      CHECK(resolved.string().rfind(kRoot.lexically_normal().string(), 0) == 0);
      ++links;
    }
  }
  CHECK(links > 50);  // the pages link to one another throughout
}

}  // namespace test_user_docs
