#!/usr/bin/env bash
# The tree-width study (docs/results.md) on a fresh Debian 12 machine: installs what is
# missing, builds examples/tree_width_study (Release) and runs it from the repository root,
# which regenerates docs/results.md, docs/study/summary.csv and docs/images/study_*.svg.
#
#   bash scripts/run_study.sh --quick     the reduced sweep (under 10 minutes on 2 cores)
#   bash scripts/run_study.sh             the full study (the thesis' 10 maps x 10 draws, ...)
#   bash scripts/run_study.sh --help      every flag (shards, threads, seed, merge, report)
#
# The runs go to build/main/tree_width_study_runs.jsonl unless --out says otherwise.
# Environment: SYLVA_BUILD_ROOT (default <repo>/build), SYLVA_JOBS (build parallelism).
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SYLVA_BUILD_ROOT:-$repo/build}/main"
jobs="${SYLVA_JOBS:-$(nproc)}"

# shellcheck source=lib/install_packages.sh
source "$repo/scripts/lib/install_packages.sh"
sylva_install_packages build-essential cmake libeigen3-dev libboost-math-dev libcli11-dev nlohmann-json3-dev gnuplot-nox

echo "==> building tree_width_study in $build" >&2
cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_BENCHMARKS=OFF -DSYLVA_BUILD_EXAMPLES=ON \
  -DCMAKE_RUNTIME_OUTPUT_DIRECTORY="$build/bin" >&2
cmake --build "$build" --target tree_width_study -j "$jobs" >&2

cd "$repo"
args=("$@")
# Default output next to the build, not in the source tree (a flag given by the user wins).
if [[ " $* " != *" --out "* && " $* " != *" merge "* && " $* " != *" report "* ]]; then
  args+=(--out "$build/tree_width_study_runs.jsonl")
fi
echo "==> $build/bin/tree_width_study ${args[*]}" >&2
exec "$build/bin/tree_width_study" --docs "$repo/docs" "${args[@]}"
