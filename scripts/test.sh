#!/usr/bin/env bash
# Builds and runs sylva's tests on a fresh Debian 12 machine.
#
#   bash scripts/test.sh                 Release build of tests, examples and benchmarks;
#                                        runs every test with ctest
#   bash scripts/test.sh --sanitize      also builds and runs the tests under
#                                        AddressSanitizer + UndefinedBehaviorSanitizer,
#                                        with clang++ (SYLVA_SANITIZE_CXX picks another)
#   bash scripts/test.sh --consumer      also installs sylva into a temporary prefix and
#                                        builds and runs tests/consumer against it
#   bash scripts/test.sh --skip-main     leaves out the Release phase (with the flags above)
#   bash scripts/test.sh --examples-only the Release phase builds examples and benchmarks and
#                                        runs their smoke runs and the repository checks, but
#                                        not the unit tests: CI's split (.ci/run), which
#                                        builds and runs the unit tests under the sanitizers
#   bash scripts/test.sh --no-python     leaves out the Python package (built by default: pip
#                                        install of python/ into a virtual environment with
#                                        Debian's python3, then pytest python/tests)
#   bash scripts/test.sh --overlap       runs the Release phase (then the consumer) beside
#                                        the sanitizer phase, each build with half the jobs,
#                                        instead of one after the other (each line of output
#                                        carries its phase's name); the build directories
#                                        stay apart
#
# Missing Debian packages are installed with apt-get (as root, or through sudo).
# Environment: SYLVA_BUILD_ROOT (default <repo>/build) holds the build directories,
# SYLVA_JOBS (default: number of cores) is the parallelism of builds and ctest,
# SYLVA_CXX (default: the system's c++, g++ on Debian) compiles the Release phase and
# SYLVA_SANITIZE_CXX (default clang++) the sanitizer phase, SYLVA_SANITIZE_DEBUG (default
# none; -g1 for file and line in its reports) its debug information; the consumer is always built
# with the system's c++, the compiler most users have.
#
# Examples and benchmarks are compiled in the Release phase so that CI notices when they
# break; ctest runs them only where an example registers a cheap smoke run through
# sylva_add_example_smoke_test() (see the top-level CMakeLists.txt), label "smoke".
set -euo pipefail

usage() { sed -n '2,32p' "$0" | sed 's/^# \{0,1\}//'; }

run_main=1
run_sanitize=0
run_consumer=0
run_python=1
overlap=0
unit_tests=ON
for arg in "$@"; do
  case "$arg" in
    --sanitize) run_sanitize=1 ;;
    --consumer) run_consumer=1 ;;
    --no-python) run_python=0 ;;
    --skip-main) run_main=0 ;;
    --examples-only) unit_tests=OFF ;;
    --overlap) overlap=1 ;;
    -h | --help) usage; exit 0 ;;
    *) echo "test.sh: unknown option '$arg'" >&2; usage >&2; exit 2 ;;
  esac
done

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_root="${SYLVA_BUILD_ROOT:-$repo/build}"
jobs="${SYLVA_JOBS:-$(nproc)}"
# The -j of the Release and sanitizer builds: with --overlap the two run side by side, so each
# takes half (see the overlap branch at the end).
build_jobs="$jobs"

# ---- dependencies ------------------------------------------------------------------------
# parallel: the study's GNU parallel test; locales: the locale sources from which a test
# compiles de_DE.UTF-8 to check number parsing under a comma-decimal locale; python3: the
# docs figure tests.
packages=(build-essential cmake libeigen3-dev catch2 libcli11-dev nlohmann-json3-dev
          libboost-math-dev libbenchmark-dev parallel locales python3)
# The sanitizer build uses clang (and its sanitizer runtimes): see the phase below.
if ((run_sanitize)) && [[ -z "${SYLVA_SANITIZE_CXX:-}" ]]; then packages+=(clang libclang-rt-dev); fi
if ((run_main)) && [[ "${SYLVA_CXX:-}" == clang++* ]]; then packages+=(clang); fi
# The Python package: pybind11, numpy and pytest from Debian, for Debian's interpreter.
# shellcheck source=lib/python_package.sh
source "$repo/scripts/lib/python_package.sh"
if ((run_python)); then packages+=("${sylva_python_packages[@]}"); fi
# shellcheck source=lib/install_packages.sh
source "$repo/scripts/lib/install_packages.sh"
sylva_install_packages "${packages[@]}"

phase_start=0
# The recap is a file, so that a phase run in the background (--overlap) adds to it too.
mkdir -p "$build_root"
recap_file="$build_root/test-recap.txt"
: >"$recap_file"
begin() { echo; echo "==> $1"; phase_start=$SECONDS; }
finish() {
  echo "==> $1 done in $((SECONDS - phase_start)) s"
  printf '%-28s %5d s  %s\n' "$1" "$((SECONDS - phase_start))" "${2:-}" >>"$recap_file"
}
# Runs ctest in build directory $1 (extra environment in the remaining arguments) and keeps
# its summary line ("100% tests passed, 0 tests failed out of N") for the recap.
summary=""
run_ctest() {
  local dir="$1"
  shift
  local log="$dir/ctest-output.log"
  # Without the builds' jobserver (MAKEFLAGS, --overlap): the compile-fail tests run builds of
  # their own, one target each.
  (cd "$dir" && env -u MAKEFLAGS "$@" ctest --output-on-failure -j "$jobs") 2>&1 | tee "$log"
  summary="$(grep -E 'tests passed|tests failed' "$log" | tail -n 1)"
}

# ---- Release: tests, examples and benchmarks ---------------------------------------------
main_phase() {
  what="tests, examples, benchmarks"
  if [[ "$unit_tests" == OFF ]]; then what="examples, benchmarks, their smoke runs"; fi
  begin "Release build ($what, ${SYLVA_CXX:-c++}) in $build_root/test"
  # -O1 rather than CMake's Release -O3: the optimizer's share of the build time grows with
  # the level (examples/victoria_park at -O2: 117 s of g++ 12, at -O1: 85 s), and the
  # tests and smoke runs do not need the speed (scripts/run_benchmarks.sh and
  # scripts/real_data_report.sh build what they time at -O3 in builds of their own). The
  # programs whose ctest runs are short even unoptimized (SYLVA_SMOKE_ONLY_OPTIONS, top-level
  # CMakeLists.txt) compile at -O0, about half the time. The examples and benchmarks keep the
  # baseline instruction set (SYLVA_NATIVE=OFF): the docs quick run (docs:regenerate_quick)
  # checks their figures against the pages, which come from baseline builds.
  cmake -S "$repo" -B "$build_root/test" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
    -DSYLVA_SMOKE_ONLY_OPTIONS="-O0" -DSYLVA_NATIVE=OFF \
    ${SYLVA_CXX:+-DCMAKE_CXX_COMPILER="$SYLVA_CXX"} \
    -DSYLVA_BUILD_TESTS=ON -DSYLVA_UNIT_TESTS="$unit_tests" -DSYLVA_BUILD_EXAMPLES=ON -DSYLVA_BUILD_BENCHMARKS=ON
  cmake --build "$build_root/test" ${build_jobs:+-j "$build_jobs"}
  finish "Release build"
  begin "ctest (Release)"
  run_ctest "$build_root/test"
  finish "ctest (Release)" "$summary"
}

# ---- AddressSanitizer + UndefinedBehaviorSanitizer ---------------------------------------
# -O0 with assertions on (no NDEBUG, so Eigen checks indices and sizes too): clang++ compiles
# the tests about 40% faster than at -O1 (tests/filter: 347 s against 583 s). Eigen runs
# 50-100x slower there, so the test files with a case tagged [slow] (ensembles, long runs)
# compile at -O1 instead (SYLVA_SLOW_TEST_OPTIONS, tests/CMakeLists.txt); -O2 -g took 3.5x
# longer and 5 GB of memory to compile the largest test file. Built with clang++
# (SYLVA_SANITIZE_CXX overrides it): the tests are template-heavy and g++ 12 spends about 3x
# longer on them (no_allocation.test.cpp: 110 s with g++ -O2, 34 s with clang++ -O2), and a
# second compiler catches what one misses.
# Without debug information: line tables (-g1) made clang++ take 15-20% longer on each test
# unit (test_tools 104 against 88 CPU-s, test_slow 171 against 135), and a sanitizer report
# still names every function of its stack. SYLVA_SANITIZE_DEBUG=-g1 adds file and line.
sanitize_phase() {
  begin "ASan+UBSan build (tests, ${SYLVA_SANITIZE_CXX:-clang++}) in $build_root/sanitize"
  cmake -S "$repo" -B "$build_root/sanitize" -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_COMPILER="${SYLVA_SANITIZE_CXX:-clang++}" \
    -DCMAKE_CXX_FLAGS_DEBUG="-O0 ${SYLVA_SANITIZE_DEBUG:-}" -DSYLVA_SLOW_TEST_OPTIONS="-O1" \
    -DSYLVA_BUILD_TESTS=ON -DSYLVA_UNIT_TESTS=ON -DSYLVA_BUILD_EXAMPLES=OFF -DSYLVA_BUILD_BENCHMARKS=OFF \
    -DSYLVA_SANITIZERS="address;undefined"
  cmake --build "$build_root/sanitize" ${build_jobs:+-j "$build_jobs"}
  finish "ASan+UBSan build"
  begin "ctest (ASan+UBSan)"
  run_ctest "$build_root/sanitize" \
    ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  finish "ctest (ASan+UBSan)" "$summary"
}

# ---- downstream consumer of the installed package ----------------------------------------
consumer_phase() {
  begin "install + tests/consumer"
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/sylva-consumer.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
  cmake -S "$repo" -B "$tmp/sylva-build" -DCMAKE_BUILD_TYPE=Release \
    -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_EXAMPLES=OFF -DSYLVA_BUILD_BENCHMARKS=OFF
  cmake --install "$tmp/sylva-build" --prefix "$tmp/prefix"
  cmake -S "$repo/tests/consumer" -B "$tmp/consumer-build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$tmp/prefix"
  found="$(sed -n 's/^sylva_DIR:PATH=//p' "$tmp/consumer-build/CMakeCache.txt")"
  if [[ "$found" != "$tmp/prefix/"* ]]; then
    echo "test.sh: the consumer found sylva in '$found', not in the fresh prefix" >&2
    exit 1
  fi
  MAKEFLAGS= cmake --build "$tmp/consumer-build" -j "$jobs"
  "$tmp/consumer-build/sylva_consumer"
  finish "install + tests/consumer" "consumer passed"
}

# ---- the Python package -------------------------------------------------------------------
# The README's Python commands (scripts/lib/python_package.sh): pip install of python/ into a
# virtual environment of Debian's python3, then pytest. The extension is compiled by clang++
# when SYLVA_CXX is clang++ (g++ otherwise), with all the jobs: with --overlap it comes last in
# its chain, when the other chain is running its tests, and a single compiler would leave a
# core idle once they end. At -O1, as the Release phase builds the examples that the tests
# compare the Python examples with (python/setup.py builds users' at -O2): a third less
# compile time, and at -O0 the tests ran 30 times longer. All but the unit that runs the
# tests' long study (planar_unicycle.cpp, python/setup.py) compile at -O0 (SYLVA_PY_OPT_REST):
# with clang++ 14 the module took 284-290 CPU-s to build (2 jobs) against 342 with every unit
# at -O1, and pytest 19 s against 8 s.
python_jobs="$jobs"
python_phase() {
  begin "Python package (pip install ./python, pytest python/tests)"
  local venv="$build_root/python-venv"
  local cxx=""
  if [[ "${SYLVA_CXX:-}" == clang++* ]]; then cxx=clang++; fi
  SYLVA_PYTHON_CXX="$cxx" SYLVA_JOBS="$python_jobs" SYLVA_PY_OPT="${SYLVA_PY_OPT:--O1}" \
    SYLVA_PY_OPT_REST="${SYLVA_PY_OPT_REST:--O0}" sylva_python_package "$venv"
  # From the repository's root, as the README says: run from python/, `python -m pytest` would
  # import the package's sources (no compiled module) ahead of the installed package. With the
  # Release phase's examples at hand, the tests also compare the Python study's output with
  # the C++ program's (SYLVA_EXAMPLES_BIN); without them those cases say they skipped.
  local examples=()
  if [[ -d "$build_root/test/examples" ]]; then examples=(SYLVA_EXAMPLES_BIN="$build_root/test/examples"); fi
  (cd "$repo" && env "${examples[@]}" "$venv/bin/python" -m pytest -q -rs python/tests) 2>&1 | tee "$build_root/pytest-output.log"
  finish "Python package" "$(grep -E ' passed| failed' "$build_root/pytest-output.log" | tail -n 1)"
}

# Prefixes each line of a phase's output with its name (--overlap interleaves two phases).
label() { sed -u "s/^/[$1] /"; }

if ((overlap && run_main && (run_sanitize || run_consumer))); then
  # Two chains side by side: the Release phase then the consumer, and the sanitizer phase;
  # both must pass. The two large builds share the cores, so that no more compilers run than
  # there are cores (each large unit's compile takes more CPU time when more processes share
  # the caches, and the builds' CPU time is most of the run); ctest and the consumer keep the
  # full -j. The consumer follows the Release phase because the sanitizer phase is the longer
  # of the two. Both chains are background jobs, so that `set -e` holds inside each (in a
  # subshell on the left of `||` bash would ignore it).
  # With GNU make (CMake's default generator here) the two builds draw their jobs from one
  # jobserver, a pipe of tokens that both makes read (MAKEFLAGS): each make runs one job of its
  # own and one more per token it takes. They start with one job each, and when the first
  # chain is done its job's token goes to the other build, so that the sanitizer build's last
  # units do not compile one at a time beside an idle core (in a local run of .ci/run, the
  # Release chain ended about 500 s before the sanitizer build did). With another generator
  # (CMAKE_GENERATOR) each build takes half the jobs, as before.
  jobserver_fd=""
  if [[ -z "${CMAKE_GENERATOR:-}" || "${CMAKE_GENERATOR}" == "Unix Makefiles" ]] &&
     make --version 2>/dev/null | grep -q '^GNU Make [4-9]'; then
    fifo="$(mktemp -u "${TMPDIR:-/tmp}/sylva-jobserver.XXXXXX")"
    mkfifo "$fifo"
    exec {jobserver_fd}<>"$fifo"
    rm -f "$fifo"
    for ((token = 2; token < jobs; ++token)); do printf '+' >&"$jobserver_fd"; done
    export MAKEFLAGS="-j$jobs --jobserver-auth=$jobserver_fd,$jobserver_fd"
    build_jobs=""
  else
    build_jobs=$((jobs > 1 ? jobs / 2 : 1))
  fi
  # A chain that is done hands its job to the other one's build (a no-op without the jobserver).
  hand_over_job() { if [[ -n "$jobserver_fd" ]]; then printf '+' >&"$jobserver_fd"; fi; }
  ( trap hand_over_job EXIT
    main_phase 2>&1 | label release
    if ((run_consumer)); then consumer_phase 2>&1 | label consumer; fi
    if ((run_python)); then python_phase 2>&1 | label python; fi ) &
  main_pid=$!
  ( trap hand_over_job EXIT
    if ((run_sanitize)); then sanitize_phase; fi ) 2>&1 | label sanitize &
  rest_pid=$!
  main_status=0
  rest_status=0
  if ! wait "$rest_pid"; then rest_status=1; fi
  if ! wait "$main_pid"; then main_status=1; fi
  if ((main_status || rest_status)); then
    echo "test.sh: a phase failed (Release and consumer: $( ((main_status)) && echo failed || echo passed)," \
      "sanitizer: $( ((rest_status)) && echo failed || echo passed))" >&2
    exit 1
  fi
else
  if ((run_main)); then main_phase; fi
  if ((run_sanitize)); then sanitize_phase; fi
  if ((run_consumer)); then consumer_phase; fi
  if ((run_python)); then python_phase; fi
fi

echo
echo "==> scripts/test.sh $* passed:"
sed 's/^/    /' "$recap_file"
