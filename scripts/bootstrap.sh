#!/usr/bin/env bash
# Set-up for condyn on Debian 12, run as root from a clean clone. Installs whatever is missing
# (apt-get), configures and builds into build/, then:
#   bash scripts/bootstrap.sh main   runs the main job: condyn validate (the chapter's five cases)
#                                    and condyn compare on the chapter truss (tables, CSV, JSON and
#                                    plots in condyn-out/compare-chapter_5_5_1/)
#   bash scripts/bootstrap.sh test   builds with warnings as errors and runs every test tier (ctest)
set -euo pipefail

mode="${1:-}"
case "$mode" in
  main | test) ;;
  *)
    echo "usage: bash scripts/bootstrap.sh main|test" >&2
    exit 2
    ;;
esac

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

# Debian 12 packages condyn builds with (see README "Dependencies").
packages=(g++ cmake ninja-build libsundials-dev libsuitesparse-dev libeigen3-dev doctest-dev
  libtomlplusplus-dev libcli11-dev)
# The test command also checks formatting and runs clang-tidy (warnings are errors in CI).
[ "$mode" = test ] && packages+=(clang-format clang-tidy)
# compare draws its plots with Debian's matplotlib (the main job, and a unit test of the plots).
packages+=(python3-matplotlib python3-numpy)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs="$(nproc 2>/dev/null || echo 2)"
werror=OFF
[ "$mode" = test ] && werror=ON
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCONDYN_WERROR="$werror" >/dev/null
cmake --build build -j "$jobs"

if [ "$mode" = main ]; then
  build/condyn validate --quiet
  echo
  exec build/condyn compare --out-dir condyn-out/compare-chapter_5_5_1
fi

# Lint: .clang-format and .clang-tidy are the project's rules, enforced here.
sources=$(find src dae models validation tests -name '*.cpp' -o -name '*.hpp' | sort)
clang-format --dry-run -Werror $sources
lint_sources=$(find src dae models validation -name '*.cpp' | sort)
run-clang-tidy -quiet -p build -j "$jobs" -extra-arg=-Wno-unknown-warning-option $lint_sources \
  >build/clang-tidy.log 2>&1 || {
  grep -E "(warning|error):" build/clang-tidy.log | sort -u >&2
  echo "bootstrap: clang-tidy found problems (full log: build/clang-tidy.log)" >&2
  exit 1
}
echo "bootstrap: clang-format and clang-tidy clean"
cd build
exec ctest --output-on-failure -j "$jobs"
