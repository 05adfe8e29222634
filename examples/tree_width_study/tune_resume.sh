#!/usr/bin/env bash
# CTest: the tuning machinery and --resume.
# - `tune` writes tuned_settings.json and tuning.md;
# - a tuned setting that differs from the shared one adds exactly one pipeline's noise and
#   density runs (setting "tuned"), after the default runs, whose count does not change;
# - a run file resumed from its first runs is byte-identical to one written in one go.
set -euo pipefail
study="$1"
dir="$2/tune_resume"
rm -rf "$dir" && mkdir -p "$dir/docs/study"
"$study" --docs "$dir/docs" --quick --threads 2 --frames 20 tune --out "$dir/tune.jsonl"
for f in tuned_settings.json tuning.md; do
  [[ -s "$dir/docs/study/$f" ]] || { echo "tune did not write $f"; exit 1; }
done
grep -q '"pipeline": "after_xyz"' "$dir/docs/study/tuned_settings.json"

default_only=$("$study" --quick --list --tuned none | awk '{n += $NF} END {print n}')
cat > "$dir/tuned.json" <<'JSON'
{"settings": [{"pipeline": "after_xyz", "occlusion": "ignored", "pixel_scale": 1.5,
               "width_scale": 1.0, "tree_position_sigma_m": 0.1},
              {"pipeline": "none", "occlusion": "ignored", "pixel_scale": 1.5,
               "width_scale": 1.0, "tree_position_sigma_m": 0.3}]}
JSON
"$study" --quick --list --tuned "$dir/tuned.json" > "$dir/list.txt"
cat "$dir/list.txt"
with_tuned=$(awk '{n += $NF} END {print n}' "$dir/list.txt")
tuned_lines=$(grep -c ' tuned ' "$dir/list.txt" || true)
# quick plan's reruns: noise 10 levels x 5 maps x 1 draw = 50; density 5 maps x (1 + 5 x 1 x 1) = 30
[[ $((with_tuned - default_only)) == 80 ]] || { echo "expected 80 tuned runs, got $((with_tuned - default_only))"; exit 1; }
[[ $tuned_lines == 2 ]] || { echo "expected tuned noise and density runs of after_xyz/ignored only"; exit 1; }
grep -q '^noise tuned after_xyz ignored 50$' "$dir/list.txt"
grep -q '^density tuned after_xyz ignored 30$' "$dir/list.txt"

common=(--quick --frames 30 --no-report --tuned none)
"$study" "${common[@]}" --limit 6 --threads 2 --out "$dir/once.jsonl"
"$study" "${common[@]}" --limit 3 --threads 1 --out "$dir/part.jsonl"
"$study" "${common[@]}" --limit 6 --threads 2 --resume "$dir/part.jsonl" --out "$dir/resumed.jsonl"
cmp "$dir/once.jsonl" "$dir/resumed.jsonl"
# A run file of other flags (the quick sweep's gain grid is not the full one's) is refused.
if "$study" --frames 30 --no-report --tuned none --limit 6 --resume "$dir/part.jsonl" --out "$dir/other.jsonl" 2> "$dir/other.err"; then
  echo "resuming from a run file of other flags was accepted"; exit 1
fi
grep -q "is not the job of this sweep" "$dir/other.err"
echo "tune writes its files; tuned runs are added for the tuned pipeline only; a resumed run file is byte-identical"
