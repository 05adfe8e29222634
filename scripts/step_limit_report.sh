#!/usr/bin/env bash
# Regenerates docs/step-limit.md and docs/step-limit.figures.json: the batched SLAM step of
# the circle world against this machine's limit at every map size, in two builds of
# bench_slam_step (clang++ when installed, Release):
#   baseline  no -march (x86-64 with SSE2, as CMake's Release and Debian build), in
#             BUILD_DIR (default build-bench-baseline, shared with compressed_report.sh)
#   native    -march=native, in NATIVE_DIR (default build-bench-native)
# each running the step, its phase prefixes, the lower-triangle memory bound and the GEMM
# peak REPETITIONS times (default 3) interleaved at random; then scripts/step_limit_report.py.
# About 40 minutes on 2 cores.
#
# Usage: bash scripts/step_limit_report.sh [BUILD_DIR [NATIVE_DIR]]
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
baseline_dir="${1:-${root}/build-bench-baseline}"
native_dir="${2:-${root}/build-bench-native}"
repetitions="${REPETITIONS:-3}"

# shellcheck source=lib/install_packages.sh
source "${root}/scripts/lib/install_packages.sh"
# shellcheck source=lib/prefer_clang.sh
source "${root}/scripts/lib/prefer_clang.sh"
sylva_install_packages build-essential cmake ninja-build libeigen3-dev libbenchmark-dev python3

filter='^BM_(StepBatched|PhasePredict|PhaseLinearize|PhaseRankUpdate|PhaseGain|PairedGain|BoundLowerReadWrite)/|^BM_GemmPeak'
for build in baseline native; do
  if [[ "${build}" == baseline ]]; then dir="${baseline_dir}"; native=OFF; else dir="${native_dir}"; native=ON; fi
  sylva_prefer_clang "${dir}"
  cmake -S "${root}" -B "${dir}" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="" -DSYLVA_NATIVE="${native}" \
    -DSYLVA_BUILD_BENCHMARKS=ON -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_EXAMPLES=OFF
  cmake --build "${dir}" -j "${JOBS:-2}" --target bench_slam_step
  echo "==> bench_slam_step (${build})" >&2
  "${dir}/bench/bench_slam_step" --benchmark_filter="${filter}" --benchmark_repetitions="${repetitions}" \
    --benchmark_enable_random_interleaving=true --benchmark_out="${dir}/step_limit.json" \
    --benchmark_out_format=json > /dev/null
done
python3 "${root}/scripts/step_limit_report.py" --baseline "${baseline_dir}/step_limit.json" \
  --native "${native_dir}/step_limit.json" --out "${root}/docs/step-limit.md" \
  --figures "${root}/docs/step-limit.figures.json" --command "bash scripts/step_limit_report.sh"
