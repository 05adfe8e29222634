#!/usr/bin/env bash
# docs/clean-build.md: the tests and examples built from a clean tree, in one sitting,
#   1. with the system's c++ (g++ on Debian; what `bash scripts/test.sh` uses),
#   2. with the same compiler, the tree issue 18 was filed against (BUILD_TIME_REFERENCE,
#      default 90b83a7, whose docs/benchmarks.md recorded 928 s; empty: not built), for that
#      issue's criterion,
#   3. with clang++ (what CI uses; SKIP_CLANG=1 leaves it out),
# each by scripts/measure_build_time.sh, then rendered by scripts/clean_build_report.py.
#
# Usage: bash scripts/clean_build_report.sh
# Environment: SYLVA_JOBS (build jobs, default: the number of cores), BUILD_TIME_REFERENCE,
# SKIP_CLANG. On 2 cores (2026-12-01) the three builds take about an hour and a half; run it
# with the machine to itself.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck source=lib/install_packages.sh
source "${root}/scripts/lib/install_packages.sh"
sylva_install_packages build-essential cmake ninja-build clang libeigen3-dev libbenchmark-dev \
  libcli11-dev nlohmann-json3-dev catch2 libboost-math-dev python3

out="${root}/build/clean-build"
mkdir -p "$out"
rm -f "$out"/*.json
load="$(cut -d ' ' -f 1-3 /proc/loadavg | sed 's/ /, /g')"
date="$(date -u +%Y-%m-%d)"

echo "==> the working tree with the system's c++"
CXX='' bash "${root}/scripts/measure_build_time.sh" "$out/gxx.json"
args=(--build "$out/gxx.json")
reference="${BUILD_TIME_REFERENCE-90b83a7}"
if [[ -n "$reference" ]]; then
  echo "==> the tree issue 18 was filed against (${reference}), the same compiler"
  CXX='' bash "${root}/scripts/measure_build_time.sh" --tree "$reference" "$out/reference.json"
  args+=(--reference "$out/reference.json")
fi
if [[ "${SKIP_CLANG:-0}" != 1 ]]; then
  echo "==> the working tree with clang++"
  CXX=clang++ bash "${root}/scripts/measure_build_time.sh" "$out/clang.json"
  args+=(--build "$out/clang.json")
fi
python3 "${root}/scripts/clean_build_report.py" "${args[@]}" --date "$date" --load "$load"
