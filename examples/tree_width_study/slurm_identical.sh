#!/usr/bin/env bash
# CTest: scripts/study_slurm.sbatch, run without Slurm as the tasks 1, 2 and 3 of an array
# --array=1-3 would run it (the SLURM_ARRAY_* variables set by hand), then
# scripts/study_slurm_merge.sbatch: the merged runs (the quick sweep's first runs, cut short)
# are byte-identical to one process with 2 threads. A task id outside 1-3 must be refused.
set -euo pipefail
study="$1"
dir="$2/slurm_identical"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
rm -rf "$dir" && mkdir -p "$dir"
common=(--quick --limit 7 --frames 40 --no-report)
"$study" "${common[@]}" --threads 2 --out "$dir/single.jsonl"
export SYLVA_STUDY_BIN="$study" SYLVA_STUDY_DIR="$dir/shards"
export SLURM_ARRAY_TASK_COUNT=3 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=3
for k in 3 1 2; do SLURM_ARRAY_TASK_ID="$k" bash "$repo/scripts/study_slurm.sbatch" "${common[@]}"; done
if SLURM_ARRAY_TASK_ID=4 bash "$repo/scripts/study_slurm.sbatch" "${common[@]}" 2>/dev/null; then
  echo "task 4 of an array 1-3 was not refused"
  exit 1
fi
bash "$repo/scripts/study_slurm_merge.sbatch" --out "$dir/merged.jsonl" "${common[@]}"
[[ $(wc -l < "$dir/single.jsonl") == 7 ]] || { echo "expected 7 runs"; exit 1; }
cmp "$dir/single.jsonl" "$dir/merged.jsonl"
echo "single-process and 3 simulated Slurm array tasks are byte-identical"
