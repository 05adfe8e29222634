#!/usr/bin/env bash
# CTest: scripts/study_parallel.sh runs the first runs of the quick sweep, cut short, as 3
# shards under GNU parallel (1 thread each) and merges them; the result is byte-identical to
# one process with 2 threads. Skipped (exit 77) when GNU parallel is not installed.
set -euo pipefail
study="$1"
dir="$2/parallel_identical"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
if ! command -v parallel >/dev/null; then
  echo "SKIPPED: GNU parallel is not installed (apt-get install parallel)"
  exit 77
fi
rm -rf "$dir" && mkdir -p "$dir"
common=(--quick --limit 7 --frames 40 --no-report)
"$study" "${common[@]}" --threads 2 --out "$dir/single.jsonl"
SYLVA_STUDY_BIN="$study" bash "$repo/scripts/study_parallel.sh" --shards 3 --jobs 3 --threads 1 \
  --dir "$dir/shards" --out "$dir/merged.jsonl" "${common[@]}"
[[ $(wc -l < "$dir/single.jsonl") == 7 ]] || { echo "expected 7 runs"; exit 1; }
cmp "$dir/single.jsonl" "$dir/merged.jsonl"
echo "single-process and 3 GNU parallel shards are byte-identical"
