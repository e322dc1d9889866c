#!/usr/bin/env bash
# Set-up for condyn on Debian 12, run as root from a clean clone. Installs whatever is missing
# (apt-get), configures and builds into build/, then:
#   bash scripts/bootstrap.sh main   runs the main job: condyn validate (the chapter's five cases)
#                                    and condyn compare on the chapter truss (tables, CSV, JSON and
#                                    plots in condyn-out/compare-chapter_5_5_1/)
#   bash scripts/bootstrap.sh test   builds with warnings as errors, lints, runs the unit and e2e
#                                    tiers again under AddressSanitizer and UndefinedBehaviorSanitizer
#                                    (build-asan/, clang), fuzzes the scene parser and model builder
#                                    for 60 s, then runs every test tier (ctest; the unit, python and
#                                    plots tests beside the fuzzer)
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
packages=(g++ cmake ninja-build libsundials-dev libsuitesparse-dev libopenblas0-pthread libeigen3-dev
  libtomlplusplus-dev libcli11-dev libhdf5-dev libspectra-dev)
# The test command also checks formatting and runs clang-tidy (warnings are errors in CI), and
# builds with clang for the sanitizers and libFuzzer (libclang-rt-14-dev has their runtimes;
# SUNDIALS' CMake package wants OpenMP, which clang finds in libomp-dev).
[ "$mode" = test ] && packages+=(doctest-dev clang-format clang-tidy clang libclang-rt-14-dev libomp-dev)
# compare and plot draw with Debian's matplotlib (the main job, and tests of the plots); plot reads
# HDF5 results with h5py.
packages+=(python3-matplotlib python3-numpy python3-h5py)
# The Python module condyn (python/, docs/python.md): pybind11 and the Python headers to build it,
# scipy for sparse models, pytest for its tests; sympy derives the IFToMM A05 reference's
# equations (validation/references/iftomm/, ctest validation/iftomm_references).
packages+=(pybind11-dev python3-dev python3-scipy)
# condyn sweep runs its studies on Dask's distributed scheduler (docs/sweep.md).
packages+=(python3-dask python3-distributed)
[ "$mode" = test ] && packages+=(python3-pytest python3-sympy)
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
# Each stage says when it starts: the time (UTC), the seconds since the command began and the CPU
# seconds (user + system) its finished processes took so far, so a CI log shows where the time
# goes, and how well the cores were kept busy (docs/benchmarks.md, "The test command").
ticks="$(getconf CLK_TCK 2>/dev/null || echo 100)"
cpu_seconds() {  # of the finished (waited for) child processes of process $1
  local stat fields
  read -r stat <"/proc/$1/stat" || { echo "?"; return; }
  read -r -a fields <<<"${stat##*) }"  # after "pid (name) ": state [0], cutime [13], cstime [14]
  echo $(((fields[13] + fields[14]) / ticks))
}
stage() { echo "bootstrap: $(date -u +%H:%M:%S) (${SECONDS} s, CPU $(cpu_seconds $$) s) $*"; }
# The main job builds the program and the Python module (build/python/condyn); the test command
# builds the test executables too (the unit and e2e tiers only in its sanitized tree, below), with
# warnings as errors. Both as a unity build: the library files are compiled in batches, which
# parse Eigen's and SUNDIALS' headers and instantiate their templates once per batch. Test files
# too, in batches, at -O1 with their common headers precompiled (CMakeLists.txt).
if [ "$mode" = main ]; then
  stage "build/: configure and build"
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCONDYN_WERROR=OFF -DCONDYN_TESTS=OFF \
    -DCMAKE_UNITY_BUILD=ON >/dev/null
  cmake --build build -j "$jobs" --target condyn condyn_python
  build/condyn validate --quiet
  echo
  exec build/condyn compare --out-dir condyn-out/compare-chapter_5_5_1
fi

# The test command keeps both cores busy: what does not depend on the step before it runs beside
# it (docs/contributing.md, "Tests"). A process it starts in the background and has not waited
# for when it stops (a failure) is stopped with it.
background=()
trap 'for p in "${background[@]}"; do kill "$p" 2>/dev/null || true; done' EXIT
# `wait_for PID WHAT LOG`: the background step's status; on failure its log's end, then exit 1.
wait_for() {
  if ! wait "$1"; then
    tail -n 60 "$3" >&2
    echo "bootstrap: $2 failed (log $3)" >&2
    exit 1
  fi
  local running=() p
  for p in "${background[@]}"; do [ "$p" = "$1" ] || running+=("$p"); done
  background=("${running[@]}")
}

# The sanitized build (its comment below) and the lint's file-by-file tree are configured beside
# the build of build/ (cmake runs on one core). UBSan without three of its checks, each a check on
# every pointer use that ASan makes in its own way or that cannot fail here: object-size (ASan
# finds every access outside an object, with its exact bounds), alignment (x86-64 loads any
# alignment; Eigen asserts its own, and this build keeps asserts) and pointer-overflow (an
# address wrapping around the address space). Their cost, about 30 % of a library batch's compile
# time and 20 % of the sanitized tests': docs/benchmarks.md, "The test command".
sanitize="-fsanitize=address,undefined -fno-sanitize=object-size,alignment,pointer-overflow"
sanitize+=" -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
mkdir -p build-lint build-asan
cmake -S . -B build-lint -G Ninja -DCMAKE_BUILD_TYPE=Release -DCONDYN_WERROR=ON -DCONDYN_TESTS=ON \
  >build-lint/configure.log 2>&1 &
lint_configure=$!
cmake -S . -B build-asan -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DCMAKE_CXX_FLAGS="$sanitize" \
  -DCONDYN_WERROR=ON -DCONDYN_TESTS=ON -DCONDYN_TEST_TIERS="unit;e2e" -DCONDYN_TESTS_OPT=-O0 \
  -DCONDYN_CLI_OPT=-O0 -DCONDYN_FUZZ=ON -DCONDYN_PYTHON=OFF -DCMAKE_UNITY_BUILD=ON \
  >build-asan/configure.log 2>&1 &
asan_configure=$!
background=("$lint_configure" "$asan_configure")
stage "build/: configure and build (g++, warnings as errors); beside it build-lint/ and" \
  "build-asan/ are configured"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCONDYN_WERROR=ON -DCONDYN_TESTS=ON \
  -DCONDYN_TEST_TIERS="convergence;validation;stress" -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build build -j "$jobs"
wait_for "$lint_configure" "configuring build-lint/" build-lint/configure.log
wait_for "$asan_configure" "configuring build-asan/" build-asan/configure.log

# Sanitizers: the unit and e2e tiers again, built by clang with ASan and UBSan into build-asan/ (its
# CONDYN_BINARY is build-asan/condyn, sanitized too, so the CLI tests run under them as well).
# Any report aborts the test. The same build has the libFuzzer harness (CONDYN_FUZZ). A unity build
# as above; line tables are all the debug information the reports need (file and line of each
# frame). The library is compiled at -O1, where the tests and the fuzzer run; the test files at -O0
# (CONDYN_TESTS_OPT), in well under half the compiler time: clang's warnings do not depend on the
# optimizer, and unoptimized code keeps every memory access of the test code for ASan to check.
# The command line and its reports too (CONDYN_CLI_OPT): 66 s of CPU less to compile, the tests
# no slower (the studies of condyn_validation at -O0 made them a third slower: they stay at -O1).
# It builds beside the lint: each keeps the cores busy where the other leaves one idle (a long
# batch, a link, clang-format's one process, the end of a clang-tidy pass).
stage "lint (clang-format, then clang-tidy); beside it build-asan/ builds (clang, ASan and UBSan)"
(
  cmake --build build-asan -j "$jobs" --target condyn_tests_unit condyn_tests_e2e condyn_fuzz_scene
  # Its own CPU seconds, apart from the lint's (read here: inside $(...) BASHPID names the
  # substitution's own process, which has no finished children).
  self=$BASHPID
  echo "bootstrap: build-asan/ built, CPU $(cpu_seconds "$self") s"
) >build-asan/build.log 2>&1 &
asan_build=$!
background+=("$asan_build")

# Lint: .clang-format and .clang-tidy are the project's rules, enforced here.
sources=$(find src dae models validation tests python -name '*.cpp' -o -name '*.hpp' | sort)
clang-format --dry-run -Werror $sources
lint_sources=$(find src dae models validation -name '*.cpp' | sort)
# clang-tidy in two passes. The path-sensitive analyzer looks only at functions of the file it is
# given, so it reads each file's own command, from a tree configured file by file (build-lint/, not
# built); misc-unused-using-decls too, which looks only there. The other checks match a unity batch
# as they match its files one by one (docs/contributing.md), so they read build/'s batches of the
# library files and the files kept out of batches (in any sub-folder).
root="$(pwd -P)"  # as CMake writes the paths
batches=$(grep -o '"file": "[^"]*"' build/compile_commands.json | cut -d'"' -f4 | grep -E \
  "/CMakeFiles/condyn(_cli|_models|_dae|_validation)?\.dir/Unity/unity_[0-9]+_cxx\.cxx$|^$root/(src|dae|models|validation)/.*\.cpp$" \
  | sort -u)
for f in $lint_sources; do  # every library file is in one pass's batches, or linted alone
  grep -qF "\"$root/$f\"" $(echo "$batches" | grep "/Unity/") /dev/null || echo "$batches" |
    grep -qxF "$root/$f" || { echo "bootstrap: $f is in no target clang-tidy reads" >&2; exit 1; }
done
lint_failed() {
  grep -E "(warning|error):" "$1" | sort -u >&2
  echo "bootstrap: clang-tidy found problems (full log: $1)" >&2
  exit 1
}
# A verdict depends only on its input, so each pass lints only the files whose input (flags, every
# file the compiler reads, checks, clang-tidy's version) scripts/lint-record.txt does not hold as
# clean, and the record is written anew when both passes are (scripts/lint_cache.py).
# CONDYN_LINT_ALL=1 lints every file whatever the record.
record=scripts/lint-record.txt
every=()
[ "${CONDYN_LINT_ALL:-0}" = 1 ] && every=(--all)
tidy() {  # $1 build folder, $2 checks, $3 log, then the files
  local db=$1 checks=$2 log=$3 pending
  shift 3
  local args=(-quiet -p "$db" -extra-arg=-Wno-unknown-warning-option "-checks=$checks")
  pending=$(python3 scripts/lint_cache.py pending --db "$db" --tidy-args "${args[*]}" \
    --record "$record" --keys "$log.keys" "${every[@]}" "$@") || exit 1
  local count
  count=$(echo "$pending" | grep -c . || true)
  echo "bootstrap: clang-tidy -checks=$checks on $count of $# files," \
    "$(($# - count)) clean at the same input by $record"
  [ -z "$pending" ] || run-clang-tidy "${args[@]}" -j "$jobs" $pending >"$log" 2>&1 ||
    lint_failed "$log"
}
tidy build-lint '-*,clang-analyzer-*,misc-unused-using-decls' build/clang-tidy-analyzer.log \
  $lint_sources
tidy build '-clang-analyzer-*,-bugprone-suspicious-include' build/clang-tidy.log $batches
python3 scripts/lint_cache.py record --record "$record" build/clang-tidy-analyzer.log.keys \
  build/clang-tidy.log.keys
[ -z "$(git status --porcelain -- "$record" 2>/dev/null)" ] ||
  echo "bootstrap: $record now holds this tree's clean lint: commit it with the change"
stage "lint: clang-format and clang-tidy clean; waiting for build-asan/"
wait_for "$asan_build" "the build of build-asan/" build-asan/build.log
tail -n 1 build-asan/build.log

# The unit and e2e tiers run here only, under the sanitizers: build/ does not build them
# (CONDYN_TEST_TIERS), so no test file is compiled twice.
stage "build-asan/: the unit and e2e tiers under the sanitizers"
(cd build-asan && ctest -L "unit|e2e" --output-on-failure -j "$jobs")

# Fuzz the scene parser and model builder for 60 s from the seed corpus. A finding (crash,
# sanitizer report, uncaught exception, refusal without the file name, non-finite model, input over
# 10 s or 2 GB) fails the command; the input is left in build-asan/fuzz-crash-* or -timeout-*.
# The fuzzer is one process; ctest runs the tests of build/ beside it on every core (the stress
# test, the longest, first), the cores shared three ways while the fuzzer runs.
stage "fuzzing for 60 s, and beside it ctest: every test of build/"
rm -rf build-asan/fuzz-corpus && mkdir -p build-asan/fuzz-corpus
build-asan/condyn_fuzz_scene -max_total_time=60 -timeout=10 -rss_limit_mb=2048 \
  -dict=tests/fuzz/scene.dict -print_final_stats=1 -artifact_prefix=build-asan/fuzz- \
  build-asan/fuzz-corpus tests/fuzz/corpus models/scenes validation/scenes \
  >build-asan/fuzz.log 2>&1 &
fuzzer=$!
background+=("$fuzzer")
ctest_status=0
(cd build && ctest --output-on-failure -j "$jobs") || ctest_status=$?
if wait "$fuzzer"; then
  echo "bootstrap: fuzzing found nothing in 60 s ($(grep -o 'number_of_executed_units: *[0-9]*' \
    build-asan/fuzz.log | grep -o '[0-9]*$') inputs; log build-asan/fuzz.log)"
else
  grep -m 1 "INFO: Seed" build-asan/fuzz.log >&2 || true  # -seed=N replays the run
  grep -v -E "^#[0-9]+|NEW_FUNC|^INFO" build-asan/fuzz.log | tail -n 60 >&2
  echo "bootstrap: the scene fuzzer found a problem (log build-asan/fuzz.log; input above)" >&2
  exit 1
fi
((ctest_status == 0)) || { echo "bootstrap: ctest in build/ failed (above)" >&2; exit 1; }
stage "done"
