#!/usr/bin/env bash
# sylva against MRPT's EKF-SLAM (mrpt::slam::CRangeBearingKFSLAM2D) on the circle world
# (bench/peers/README.md):
#   1. installs libmrpt-dev (and the other build dependencies) if missing (apt-get),
#   2. configures a Release build with the benchmarks (default build dir: build-peers) and
#      builds peers_agreement, bench_peers_native and bench_peers_baseline,
#   3. runs the agreement check (sylva and MRPT on the same two laps at N = 50 and 200; stops
#      here if they disagree),
#   4. for each N: runs bench_peers_native (every family: MRPT kfEKFNaive and
#      kfEKFAlaDavison, sylva's three fusions built with -march=native), then
#      bench_peers_baseline (the same families, sylva's built for baseline x86-64). MRPT is
#      the same library in both, and runs in both, so that each program's ratios pair
#      figures of one run (docs/benchmarks.md judges its criteria run by run). JSON to
#      BUILD_DIR/bench/peers_native_<N>.json and peers_baseline_<N>.json,
#   5. prints the step times and the ratios at each N (bench/peers/peer_report.py), also
#      written to BUILD_DIR/bench/peers.md.
#
# Usage: scripts/run_peer_benchmarks.sh [BUILD_DIR]
# Environment:
#   JOBS         parallel build jobs (default 2)
#   SIZES        map sizes N (default 50,100,200,500,1000,2000)
#   STEPS        lap-2 steps per timed iteration (default 10)
#   NAIVE_MAX_N  largest N for MRPT kfEKFNaive (default 2000)
#   REPETITIONS  repetitions per benchmark (default 3; the report uses their medians)
#   WHOLE_SIZES  map sizes N (a subset of SIZES) at which the baseline program also times the
#                whole run, both laps from an empty map: MRPT kfEKFAlaDavison against sylva's
#                replica of its fusion through the compressed EKF (default none: at N = 2000
#                MRPT's whole run took 35 to 41 minutes per repetition on the 2-core
#                machine of 2026-11-30, so three repetitions take about two hours)
#   BENCH_ARGS   extra Google Benchmark flags for both runs
#   CXX          the compiler for sylva's side, read at the first configure of BUILD_DIR
#                (e.g. CXX=clang++ scripts/run_peer_benchmarks.sh build-peers-clang): sylva's
#                time is mostly Eigen's dense kernels, whose speed depends on the compiler
#                (on the 2-core AVX-512 machine these were written on, clang++ 14's build
#                ran the batched step at N = 1000 about twice as fast as g++ 12's); the
#                report names the compiler.
#
# Runtime: about 20 minutes on a 2-core machine with the defaults (plus the first build), more
# than half of it MRPT kfEKFNaive at N = 2000 (twice: once per program): O(n^3), several seconds
# per step, so one
# iteration of STEPS steps per repetition is all it gets (plus one checked step).
# NAIVE_MAX_N=1000 leaves it out.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-${root}/build-peers}"
jobs="${JOBS:-2}"
sizes="${SIZES:-50,100,200,500,1000,2000}"
steps="${STEPS:-10}"
naive_max_n="${NAIVE_MAX_N:-2000}"
repetitions="${REPETITIONS:-3}"
out_dir="${build_dir}/bench"

# shellcheck source=lib/install_packages.sh
source "${root}/scripts/lib/install_packages.sh"
sylva_install_packages cmake g++ libeigen3-dev libbenchmark-dev libmrpt-dev python3

cmake -S "${root}" -B "${build_dir}" -DCMAKE_BUILD_TYPE=Release \
  -DSYLVA_BUILD_BENCHMARKS=ON -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_EXAMPLES=OFF -DSYLVA_WITH_MRPT=ON
cmake --build "${build_dir}" -j "${jobs}" --target peers_agreement bench_peers_native bench_peers_baseline
peers="${build_dir}/bench/peers"

echo "==> agreement of sylva and MRPT (two laps, N = 50 and 200)"
"${peers}/peers_agreement" 50 200

mkdir -p "${out_dir}"
rm -f "${out_dir}"/peers_native_*.json "${out_dir}"/peers_baseline_*.json
# One N at a time (one map in memory), native then baseline, and within a run the families'
# repetitions in random order, so that a slow spell of a shared machine does not land on one
# family only.
common=(--peers_steps="${steps}" --peers_naive_max_n="${naive_max_n}"
        --benchmark_repetitions="${repetitions}" --benchmark_enable_random_interleaving=true
        --benchmark_context=nproc="$(nproc)")
native=()
baseline=()
IFS=',' read -r -a size_list <<< "${sizes}"
for n in "${size_list[@]}"; do
  echo "==> N = ${n}: MRPT and sylva built with -march=native"
  # shellcheck disable=SC2086  # BENCH_ARGS is a list of flags on purpose
  "${peers}/bench_peers_native" --peers_sizes="${n}" "${common[@]}"     --benchmark_out="${out_dir}/peers_native_${n}.json" --benchmark_out_format=json ${BENCH_ARGS:-}
  echo "==> N = ${n}: MRPT and sylva built for baseline x86-64"
  whole=()
  if [[ ",${WHOLE_SIZES:-}," == *",${n},"* ]]; then whole=(--peers_whole_sizes="${n}"); fi
  # shellcheck disable=SC2086
  "${peers}/bench_peers_baseline" --peers_sizes="${n}" "${whole[@]}" "${common[@]}"     --benchmark_out="${out_dir}/peers_baseline_${n}.json" --benchmark_out_format=json ${BENCH_ARGS:-}
  native+=("${out_dir}/peers_native_${n}.json")
  baseline+=("${out_dir}/peers_baseline_${n}.json")
done

echo
python3 "${root}/bench/peers/peer_report.py" --native "${native[@]}" --baseline "${baseline[@]}" \
  --out "${out_dir}/peers.md" --command "scripts/run_peer_benchmarks.sh"
