// libFuzzer harness for the scene parser and model builder (docs/contributing.md "Tests", fuzzing).
//
// Every input is scene text. The parser and the builder must either accept it or refuse it with a
// condyn::SceneError whose message starts with the file name ("fuzz.toml: ..." or
// "fuzz.toml:LINE: ..."), as the CLI prints it before exiting 2. Anything else is a finding and
// aborts: a crash, a sanitizer report, a hang (-timeout), an allocation beyond -rss_limit_mb, any
// other exception escaping build_model() (the CLI would report it as a failure after the input
// was accepted, exit 1, without naming the file, key or line), and an accepted model that is not
// finite (M, C, K, A, u(0), v(0), the loads f(t), or the constraint right-hand sides g, g', g'' at
// nine times across [0, t_end]): the silent inf/NaN the project forbids.
//
// Build (-O1 -g without NDEBUG, so Eigen's bounds assertions are on too):
//   cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCONDYN_FUZZ=ON
//     -DCONDYN_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
//     -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g"
//   cmake --build build-fuzz --target condyn_fuzz_scene
// Run (NEW_CORPUS_DIR, an empty folder, collects the inputs that found new code):
//   build-fuzz/condyn_fuzz_scene -max_total_time=60 -timeout=10 -rss_limit_mb=2048
//     -dict=tests/fuzz/scene.dict NEW_CORPUS_DIR tests/fuzz/corpus models/scenes validation/scenes
// Replay one input: build-fuzz/condyn_fuzz_scene FILE (CONDYN_FUZZ_VERBOSE=1 prints the refusal).
#include <Eigen/Sparse>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"

namespace {

[[noreturn]] void finding(const char* what, const char* message) {
  std::fprintf(stderr, "fuzz_scene: %s: %s\n", what, message);
  std::abort();
}

void check_finite(bool finite, const char* what) {
  if (!finite) finding("accepted scene is not finite", what);
}

bool all_finite(const Eigen::SparseMatrix<double>& m) {
  for (Eigen::Index k = 0; k < m.nonZeros(); ++k) {
    if (!std::isfinite(m.valuePtr()[k])) return false;
  }
  return true;
}

void check_accepted(const condyn::Model& model, const condyn::SolveSpec& settings) {
  check_finite(all_finite(model.M), "M");
  check_finite(all_finite(model.C), "C");
  check_finite(all_finite(*model.K), "K");
  check_finite(all_finite(model.A), "A");
  check_finite(model.u0.allFinite(), "u(0)");
  check_finite(model.v0.allFinite(), "v(0)");
  const double t_end = settings.t_end;
  for (int s = 0; s <= 8; ++s) {
    const double t = t_end * s / 8.0;
    check_finite(model.applied_forces(t).allFinite(), "loads f(t)");
    for (int order = 0; order <= 2; ++order) {
      check_finite(model.position_rhs(order, t).allFinite(), "constraint right-hand side g(t)");
    }
  }
  // The output grid is bounded (at most 10^7 rows) and ends at t_end.
  const auto times = settings.output_times();
  if (times.empty() || !(times.back() == t_end)) {
    finding("accepted scene", "output grid does not end at t_end");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const condyn::SceneSpec spec = condyn::parse_scene_text(text, "fuzz.toml");
    check_accepted(condyn::build_model(spec), spec.solve);
  } catch (const condyn::SceneError& e) {
    const std::string msg = e.what();
    if (msg.rfind("fuzz.toml:", 0) != 0) finding("SceneError does not name the file", e.what());
    if (std::getenv("CONDYN_FUZZ_VERBOSE") != nullptr) std::fprintf(stderr, "%s\n", e.what());
  } catch (const std::exception& e) {
    finding("exception other than SceneError", e.what());
  }
  return 0;
}
