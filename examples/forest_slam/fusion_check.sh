#!/usr/bin/env bash
# forest_slam's --fusion (ctest forest_slam:fusion): the default forest (about two seconds a
# run), each model's observations fused in one batched update (the default) and one at a time
# (--fusion sequential). The two are different estimators of the same frames (the sequential
# one relinearizes after each observation), so their map and trajectory errors must differ,
# which shows the flag reaches the filter, and stay finite and of the same size (within a factor
# of 3 of each other), which shows neither run breaks.
# Usage: fusion_check.sh FOREST_SLAM_BINARY
set -euo pipefail
bin="$(realpath "$1")"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/forest_fusion.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
"$bin" --json --svg-prefix "" > batched.json
"$bin" --json --svg-prefix "" --fusion sequential > sequential.json
python3 - batched.json sequential.json <<'PY'
import json, math, sys
batched, sequential = (json.load(open(p)) for p in sys.argv[1:3])
status = 0
for key in ("with_width", "without_width", "width_first_sight"):
    for error in ("landmark_error", "trajectory_error"):
        b, s = batched[key][error], sequential[key][error]
        print(f"fusion_check: {key} {error}: batched {b}, sequential {s}")
        if b is None or s is None or not (math.isfinite(b) and math.isfinite(s)) or b == s or max(b, s) > 3 * min(b, s):
            print(f"fusion_check: {key} {error}: expected two finite, different errors within a factor of 3",
                  file=sys.stderr)
            status = 1
sys.exit(status)
PY
