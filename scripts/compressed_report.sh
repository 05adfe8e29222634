#!/usr/bin/env bash
# Regenerates docs/compressed-ekf.md and docs/compressed-ekf.figures.json: a Release build of
# bench_compressed_ekf (baseline x86-64: no -march, as CMake's Release and Debian build) in
# BUILD_DIR (default build-bench-baseline), its lap-2 families run REPETITIONS times (default
# 3) interleaved at random, then scripts/compressed_report.py. About 5 minutes on 2 cores.
#
# Usage: bash scripts/compressed_report.sh [BUILD_DIR]
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-${root}/build-bench-baseline}"
repetitions="${REPETITIONS:-3}"

# shellcheck source=lib/install_packages.sh
source "${root}/scripts/lib/install_packages.sh"
sylva_install_packages build-essential cmake ninja-build libeigen3-dev libbenchmark-dev python3

# clang++ when installed, as scripts/run_benchmarks.sh (CXX picks another at the first configure).
if [[ ! -f "${build_dir}/CMakeCache.txt" && -z "${CXX:-}" ]] && command -v clang++ > /dev/null; then
  export CXX=clang++
fi
cmake -S "${root}" -B "${build_dir}" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DSYLVA_BUILD_BENCHMARKS=ON -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_EXAMPLES=OFF
cmake --build "${build_dir}" -j "${JOBS:-2}" --target bench_compressed_ekf
"${build_dir}/bench/bench_compressed_ekf" --benchmark_filter='LapTwo' \
  --benchmark_repetitions="${repetitions}" --benchmark_enable_random_interleaving=true \
  --benchmark_out="${build_dir}/bench_compressed_ekf.json" --benchmark_out_format=json
python3 "${root}/scripts/compressed_report.py" "${build_dir}/bench_compressed_ekf.json" \
  --out "${root}/docs/compressed-ekf.md" --figures "${root}/docs/compressed-ekf.figures.json" \
  --command "bash scripts/compressed_report.sh"
