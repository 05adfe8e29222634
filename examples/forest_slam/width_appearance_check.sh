#!/usr/bin/env bash
# forest_slam's width comparison without ids (ctest forest_slam:width_appearance): a still
# camera sees one trunk for ten frames, then, at the same [u, v], a trunk twice as wide (a
# nearer one standing in front of it). Without ids, a landmark that predicts [u, v] only
# takes that sighting when it is compared on [u, v] alone (--no-width-appearance): one tree
# added. With the width predicted from its last sighting (the default), the sighting starts a
# new tree: two. Checked for the two pipelines whose young trees are points (with_width and
# without_width).
# Usage: width_appearance_check.sh FOREST_SLAM_BINARY
set -euo pipefail
bin="$1"
# shellcheck source=still_camera.sh
source "$(dirname "${BASH_SOURCE[0]}")/still_camera.sh" forest_width_appearance
{
  echo "# time_s, u_px, v_px, w_px"
  for k in $(seq 1 10); do echo "0.$((k - 1))1, 320, 300, 20"; done
  for k in $(seq 1 5); do echo "1.$((k - 1))1, 320, 300, 40"; done
} > "$tmp/detections.csv"
for run in width uv; do
  flags=()
  [[ "$run" == uv ]] && flags=(--no-width-appearance)
  "$bin" --detections "$tmp/detections.csv" --camera "$tmp/camera.csv" --initial-state "$tmp/initial.csv" \
    --association nn --svg-prefix "" --json "${flags[@]}" > "$tmp/$run.json"
done
status=0
for pipeline in with_width without_width; do
  added() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))[sys.argv[2]]["added"])' "$tmp/$1.json" "$pipeline"; }
  with=$(added width)
  without=$(added uv)
  echo "width_appearance_check: $pipeline: $with trees added with the width comparison, $without without"
  if [[ "$with" != 2 || "$without" != 1 ]]; then
    echo "width_appearance_check: $pipeline: expected 2 trees with the width comparison and 1 without" >&2
    status=1
  fi
done
exit "$status"
