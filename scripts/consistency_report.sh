#!/usr/bin/env bash
# Regenerates docs/consistency.md:
#   1. a Release build of examples/consistency in BUILD_DIR (default build-consistency; clang++
#      when installed and CXX is not set: it compiles sylva's templates about 3x faster),
#   2. consistency --suite planar,monocular,monocular-forests --json,
#      consistency --suite monocular-factors --runs FACTOR_RUNS --json and
#      consistency --suite monocular-tuning --json and
#      consistency --suite monocular-motion,monocular-gauge,monocular-manifold --json (THREADS threads),
#   3. scripts/consistency_report.py, which writes the page from the four JSON files (kept in
#      BUILD_DIR).
# About 40 minutes on 2 cores. Usage: bash scripts/consistency_report.sh [BUILD_DIR]
# Environment: THREADS (default 2), JOBS (default 2), FACTOR_RUNS (default 10), RAISED_ACCEL
# (default 3 m/s^2).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-${root}/build-consistency}"
threads="${THREADS:-2}"
jobs="${JOBS:-2}"
factor_runs="${FACTOR_RUNS:-10}"
# The raised acceleration noise of the factorial: the sharpest turn of the default path turns
# the velocity by 90 degrees (1.4 m/s at 1 m/s) in about 4 s, which a white acceleration of
# sigma_a covers at one sigma when sigma_a sqrt(T dt) = 1.4 m/s, sigma_a = 2.3 m/s^2 at dt = 0.1 s.
raised_accel="${RAISED_ACCEL:-3}"

# shellcheck source=lib/install_packages.sh
source "${root}/scripts/lib/install_packages.sh"
# shellcheck source=lib/prefer_clang.sh
source "${root}/scripts/lib/prefer_clang.sh"
sylva_install_packages build-essential cmake libeigen3-dev libcli11-dev nlohmann-json3-dev libboost-math-dev python3

sylva_prefer_clang "${build_dir}"
cmake -S "${root}" -B "${build_dir}" -DCMAKE_BUILD_TYPE=Release -DSYLVA_NATIVE=OFF \
  -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_BENCHMARKS=OFF -DSYLVA_BUILD_EXAMPLES=ON
cmake --build "${build_dir}" -j "${jobs}" --target consistency

program="${build_dir}/examples/consistency/consistency"
"${program}" --suite planar,monocular,monocular-forests --threads "${threads}" --json > "${build_dir}/consistency_suites.json"
"${program}" --suite monocular-factors --runs "${factor_runs}" --raised-accel "${raised_accel}" --threads "${threads}" --json > "${build_dir}/consistency_factors.json"
"${program}" --suite monocular-tuning --threads "${threads}" --json > "${build_dir}/consistency_tuning.json"
"${program}" --suite monocular-motion,monocular-gauge,monocular-manifold --threads "${threads}" --json > "${build_dir}/consistency_motion.json"
python3 "${root}/scripts/consistency_report.py" "${build_dir}/consistency_suites.json" \
  "${build_dir}/consistency_factors.json" "bash scripts/consistency_report.sh" "${raised_accel}" \
  "${build_dir}/consistency_tuning.json" "${build_dir}/consistency_motion.json" > "${root}/docs/consistency.md"
echo "consistency_report.sh: wrote docs/consistency.md"
