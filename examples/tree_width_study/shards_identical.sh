#!/usr/bin/env bash
# CTest: the first runs of the quick sweep, cut short, give byte-identical run files from one
# process with 2 threads and from 3 shards merged (each with 1 thread).
set -euo pipefail
study="$1"
dir="$2/shards_identical"
rm -rf "$dir" && mkdir -p "$dir"
common=(--quick --limit 7 --frames 40 --no-report)
"$study" "${common[@]}" --threads 2 --out "$dir/single.jsonl"
for k in 1 2 3; do "$study" "${common[@]}" --threads 1 --shard "$k/3" --out "$dir/part$k.jsonl"; done
"$study" merge --out "$dir/merged.jsonl" "$dir/part3.jsonl" "$dir/part1.jsonl" "$dir/part2.jsonl"
[[ $(wc -l < "$dir/single.jsonl") == 7 ]] || { echo "expected 7 runs"; exit 1; }
cmp "$dir/single.jsonl" "$dir/merged.jsonl"
echo "single-process and 3-shard runs are byte-identical"
