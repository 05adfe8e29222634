#!/usr/bin/env bash
# Regenerates docs/compressed-ekf.md and docs/compressed-ekf.figures.json: a Release build of
# bench_compressed_ekf (baseline x86-64: no -march, as CMake's Release and Debian build) in
# BUILD_DIR (default build-bench-baseline), its lap-2 families run REPETITIONS times (default
# 3) interleaved at random; then, when the Victoria Park data are there (DATA_DIR, default
# ../shared/data), examples/victoria_park --compare-compressed over the whole run (both
# variants, plain and compressed, the textbook linearization); the circle world's whole run
# plain and compressed (WholeRunAgreement, N = 1000 and 2000), and compressed alone for seven
# regions (WholeRunRegions, N = 2000); then
# scripts/compressed_report.py. About 15 minutes on 2 cores.
#
# PEERS_WHOLE=1 also builds bench_peers_baseline (installs libmrpt-dev) and times MRPT's
# kfEKFAlaDavison against sylva's compressed EKF over the whole run at N = 2000,
# PEERS_WHOLE_REPETITIONS times (default 3; MRPT takes over half an hour per repetition), for
# the page's "Against MRPT's whole run". Without it that section says it was not run.
#
# Usage: bash scripts/compressed_report.sh [BUILD_DIR]
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-${root}/build-bench-baseline}"
repetitions="${REPETITIONS:-3}"
data_dir="${DATA_DIR:-${root}/../shared/data}"

# shellcheck source=lib/install_packages.sh
source "${root}/scripts/lib/install_packages.sh"
# shellcheck source=lib/prefer_clang.sh
source "${root}/scripts/lib/prefer_clang.sh"
sylva_install_packages build-essential cmake ninja-build libeigen3-dev libbenchmark-dev libcli11-dev \
  nlohmann-json3-dev libboost-math-dev python3

peers_whole="${PEERS_WHOLE:-0}"
mrpt_flag=()
targets=(bench_compressed_ekf victoria_park)
if [[ "${peers_whole}" == 1 ]]; then
  sylva_install_packages libmrpt-dev
  mrpt_flag=(-DSYLVA_WITH_MRPT=ON)
  targets+=(bench_peers_baseline)
fi

sylva_prefer_clang "${build_dir}"
cmake -S "${root}" -B "${build_dir}" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSYLVA_NATIVE=OFF \
  -DSYLVA_BUILD_BENCHMARKS=ON -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_EXAMPLES=ON "${mrpt_flag[@]}"
cmake --build "${build_dir}" -j "${JOBS:-2}" --target "${targets[@]}"
"${build_dir}/bench/bench_compressed_ekf" --benchmark_filter='LapTwo' \
  --benchmark_repetitions="${repetitions}" --benchmark_enable_random_interleaving=true \
  --benchmark_out="${build_dir}/bench_compressed_ekf.json" --benchmark_out_format=json
echo "==> the whole run, plain and compressed, and compressed for several regions (WholeRun*: the plain run at N = 2000 takes minutes)" >&2
"${build_dir}/bench/bench_compressed_ekf" --benchmark_filter='WholeRun' \
  --benchmark_out="${build_dir}/bench_compressed_whole.json" --benchmark_out_format=json
vp_args=()
if [[ -f "${data_dir}/victoria-park/measurements.dat" ]]; then
  echo "==> victoria_park --compare-compressed (the whole run, both variants)" >&2
  "${build_dir}/examples/victoria_park/victoria_park" --data "${data_dir}/victoria-park" --compare-compressed \
    --linearization current --json > "${build_dir}/victoria_park_compressed.json"
  vp_args=(--victoria-park "${build_dir}/victoria_park_compressed.json")
else
  echo "compressed_report.sh: no Victoria Park data in ${data_dir}/victoria-park; its section says so" >&2
fi
peers_args=()
if [[ "${peers_whole}" == 1 ]]; then
  echo "==> MRPT kfEKFAlaDavison against sylva compressed, the whole run at N = 2000 (over half an hour per repetition)" >&2
  "${build_dir}/bench/peers/bench_peers_baseline" --peers_sizes=2000 --peers_whole_sizes=2000 --benchmark_filter=whole \
    --benchmark_repetitions="${PEERS_WHOLE_REPETITIONS:-3}" \
    --benchmark_out="${build_dir}/bench_peers_whole.json" --benchmark_out_format=json
  peers_args=(--peers-whole "${build_dir}/bench_peers_whole.json")
fi
python3 "${root}/scripts/compressed_report.py" "${build_dir}/bench_compressed_ekf.json" "${vp_args[@]}" "${peers_args[@]}" \
  --whole-run "${build_dir}/bench_compressed_whole.json" \
  --out "${root}/docs/compressed-ekf.md" --figures "${root}/docs/compressed-ekf.figures.json" \
  --command "bash scripts/compressed_report.sh"
