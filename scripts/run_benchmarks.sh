#!/usr/bin/env bash
# Regenerates docs/benchmarks.md and docs/benchmarks.svg:
#   1. configures a Release build with the benchmarks on (default build dir: build-bench),
#   2. builds bench_ekf_update,
#   3. runs it with repetitions and random interleaving, raw JSON to
#      BUILD_DIR/benchmarks.json (kept out of the repository; only the report is committed),
#   4. turns the JSON into the report with scripts/bench_report.py.
#
# Usage: scripts/run_benchmarks.sh [BUILD_DIR]
# Environment:
#   REPETITIONS  repetitions per benchmark (default 5)
#   JOBS         parallel build jobs (default 1)
#   BENCH_ARGS   extra arguments for bench_ekf_update, e.g. --benchmark_filter=Update
# The whole run takes three to five minutes on a busy 2-core machine.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-${root}/build-bench}"
repetitions="${REPETITIONS:-5}"
jobs="${JOBS:-1}"
json="${build_dir}/benchmarks.json"

cmake -S "${root}" -B "${build_dir}" -DCMAKE_BUILD_TYPE=Release \
  -DSYLVA_BUILD_BENCHMARKS=ON -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_EXAMPLES=OFF
cmake --build "${build_dir}" --target bench_ekf_update -j "${jobs}"

# shellcheck disable=SC2086  # BENCH_ARGS is a list of flags on purpose
"${build_dir}/bench/bench_ekf_update" \
  --benchmark_repetitions="${repetitions}" \
  --benchmark_enable_random_interleaving=true \
  --benchmark_context=nproc="$(nproc)" \
  --benchmark_out="${json}" --benchmark_out_format=json \
  ${BENCH_ARGS:-}

python3 "${root}/scripts/bench_report.py" "${json}" \
  --out "${root}/docs/benchmarks.md" --svg "${root}/docs/benchmarks.svg" \
  --command "scripts/run_benchmarks.sh"
