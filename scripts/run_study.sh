#!/usr/bin/env bash
# The tree-width study (docs/results.md) on a fresh Debian 12 machine: installs what is
# missing, builds examples/tree_width_study (Release) and runs it from the repository root,
# which regenerates docs/results.md, docs/study/summary.csv and docs/images/study_*.svg.
#
#   bash scripts/run_study.sh --quick     the reduced sweep (under 10 minutes on 2 cores)
#   bash scripts/run_study.sh             the full study (the thesis' 10 maps x 10 draws, ...)
#   bash scripts/run_study.sh --help      every flag (shards, threads, seed, merge, report)
#   bash scripts/run_study.sh tune        each pipeline's best setting, chosen on tuning maps
#                                         (about 15 minutes on 2 cores): writes
#                                         docs/study/tuned_settings.json and tuning.md; the study
#                                         reruns its sweeps with them (run `tune` first)
#
# The tuning runs go to build/main/tree_width_study_tuning.jsonl.
# The runs go to build/main/tree_width_study_runs.jsonl unless --out says otherwise.
# Shards on several cores or machines (GNU parallel, a Slurm job array): docs/study/cluster.md.
# Environment: SYLVA_BUILD_ROOT (default <repo>/build), SYLVA_JOBS (build parallelism).
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SYLVA_BUILD_ROOT:-$repo/build}/main"
jobs="${SYLVA_JOBS:-$(nproc)}"

# shellcheck source=lib/study.sh
source "$repo/scripts/lib/study.sh"
sylva_study_build "$repo" "$build" "$jobs"

cd "$repo"
args=("$@")
# Default output next to the build, not in the source tree (a flag given by the user wins).
if [[ " $* " == *" tune "* ]]; then
  if [[ " $* " != *" --out "* && " $* " != *" --from "* ]]; then
    args+=(--out "$build/tree_width_study_tuning.jsonl")
  fi
elif [[ " $* " != *" --out "* && " $* " != *" merge "* && " $* " != *" report "* ]]; then
  args+=(--out "$build/tree_width_study_runs.jsonl")
fi
echo "==> $build/bin/tree_width_study ${args[*]}" >&2
exec "$build/bin/tree_width_study" --docs "$repo/docs" "${args[@]}"
