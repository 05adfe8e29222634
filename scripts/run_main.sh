#!/usr/bin/env bash
# Builds sylva's main example on a fresh Debian 12 machine and runs it on its default
# scenario: monocular EKF-SLAM in a simulated forest, with and without the tree-width sensor
# (examples/forest_slam).
#
#   bash scripts/run_main.sh                 default scenario; writes forest_slam_*.svg here
#   bash scripts/run_main.sh --json          extra arguments go to forest_slam (--help lists them)
#
# Missing Debian packages are installed with apt-get (as root, or through sudo).
# Environment: SYLVA_BUILD_ROOT (default <repo>/build) holds the build directory,
# SYLVA_JOBS (default: number of cores) is the build parallelism.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SYLVA_BUILD_ROOT:-$repo/build}/main"
jobs="${SYLVA_JOBS:-$(nproc)}"

# ---- dependencies (the library: Eigen; the example: CLI11, nlohmann_json, Boost.Math) ----
packages=(build-essential cmake libeigen3-dev libboost-math-dev libcli11-dev nlohmann-json3-dev)
# shellcheck source=lib/install_packages.sh
source "$repo/scripts/lib/install_packages.sh"
sylva_install_packages "${packages[@]}"

# ---- configure and build (build output goes to stderr so that stdout is the program's) ----
echo "==> building forest_slam in $build" >&2
cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_BENCHMARKS=OFF -DSYLVA_BUILD_EXAMPLES=ON \
  -DCMAKE_RUNTIME_OUTPUT_DIRECTORY="$build/bin" >&2
cmake --build "$build" --target forest_slam -j "$jobs" >&2

# ---- run ------------------------------------------------------------------------------------
echo "==> $build/bin/forest_slam $*" >&2
exec "$build/bin/forest_slam" "$@"
