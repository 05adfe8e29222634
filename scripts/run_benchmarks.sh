#!/usr/bin/env bash
# Regenerates docs/benchmarks.md (and docs/images/benchmarks_step.svg) and
# docs/update-benchmarks.md (and docs/update-benchmarks.svg):
#   1. a Release build of the benchmarks with -march=native in BUILD_DIR (default
#      build-bench-native; CXX picks the compiler at the first configure, default clang++ when
#      installed: Eigen's AVX-512 kernels run about 1.6x faster with clang++ 14 than with
#      g++ 12 on the machine these were written on, and the report names the compiler),
#   2. bench_slam_step (the circle world's step against N, the read/write bounds and the GEMM
#      peak in one run), bench_forest_slam (the monocular frame split) and bench_ekf_update
#      (single updates, update forms), with repetitions and random interleaving,
#   3. the side-by-side run with MRPT (scripts/run_peer_benchmarks.sh, which installs Debian's
#      libmrpt-dev; SKIP_PEERS=1 leaves it out, and the report then says MRPT was not run),
#   4. the reports: scripts/step_report.py and scripts/bench_report.py,
#   5. the compressed EKF's page (scripts/compressed_report.sh, a baseline build of its own;
#      SKIP_COMPRESSED=1 leaves it out).
# Raw JSON stays in the build directories; only the reports are committed.
#
# Usage: bash scripts/run_benchmarks.sh [BUILD_DIR]
# Environment: REPETITIONS (default 5), JOBS (build jobs, default 2), SKIP_PEERS, SKIP_COMPRESSED.
# The build time of the tests and examples has a script and page of its own:
# scripts/clean_build_report.sh, docs/clean-build.md.
# On a 2-core machine (2026-11-30): bench_slam_step alone took 36 minutes with its 5
# repetitions, and the whole run about an hour.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-${root}/build-bench-native}"
repetitions="${REPETITIONS:-5}"
jobs="${JOBS:-2}"

# shellcheck source=lib/install_packages.sh
source "${root}/scripts/lib/install_packages.sh"
# shellcheck source=lib/prefer_clang.sh
source "${root}/scripts/lib/prefer_clang.sh"
sylva_install_packages build-essential cmake ninja-build clang libeigen3-dev libbenchmark-dev \
  libcli11-dev nlohmann-json3-dev catch2 libboost-math-dev gnuplot-nox python3

sylva_prefer_clang "${build_dir}"
cmake -S "${root}" -B "${build_dir}" -DCMAKE_BUILD_TYPE=Release -DSYLVA_NATIVE=ON \
  -DSYLVA_BUILD_BENCHMARKS=ON -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_EXAMPLES=OFF
cmake --build "${build_dir}" -j "${jobs}" --target bench_slam_step bench_forest_slam bench_ekf_update

run() {
  local name="$1"
  shift
  echo "==> ${name}"
  "${build_dir}/bench/${name}" --benchmark_repetitions="${repetitions}" \
    --benchmark_enable_random_interleaving=true --benchmark_context=nproc="$(nproc)" \
    --benchmark_out="${build_dir}/${name}.json" --benchmark_out_format=json "$@"
}
run bench_slam_step
run bench_forest_slam --benchmark_filter=FrameSplit
run bench_ekf_update

peer_args=()
if [[ "${SKIP_PEERS:-0}" != 1 ]]; then
  bash "${root}/scripts/run_peer_benchmarks.sh" "${root}/build-peers"
  peer_args=(--peers-native "${root}"/build-peers/bench/peers_native_*.json
             --peers-baseline "${root}"/build-peers/bench/peers_baseline_*.json)
fi

python3 "${root}/scripts/step_report.py" --step "${build_dir}/bench_slam_step.json" \
  --forest "${build_dir}/bench_forest_slam.json" "${peer_args[@]}" \
  --out "${root}/docs/benchmarks.md" --plot "${root}/docs/images/benchmarks_step.svg" \
  --command "bash scripts/run_benchmarks.sh"
python3 "${root}/scripts/bench_report.py" "${build_dir}/bench_ekf_update.json" \
  --out "${root}/docs/update-benchmarks.md" --svg "${root}/docs/update-benchmarks.svg" \
  --command "bash scripts/run_benchmarks.sh"
if [[ "${SKIP_COMPRESSED:-0}" != 1 ]]; then
  bash "${root}/scripts/compressed_report.sh"
fi
