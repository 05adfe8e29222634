#!/usr/bin/env bash
# forest_slam's removal of unconfirmed landmarks (ctest forest_slam:unconfirmed): a still camera
# sees one trunk in all ten frames and another only in frame 2. With --unconfirmed-after 3
# --confirm-sightings 2 the second, sighted once, is removed three frames later, and the first
# stays; by default (0) nothing is removed. Checked for the three pipelines, without ids.
# Usage: unconfirmed_check.sh FOREST_SLAM_BINARY
set -euo pipefail
bin="$1"
# shellcheck source=still_camera.sh
source "$(dirname "${BASH_SOURCE[0]}")/still_camera.sh" forest_unconfirmed
{
  echo "# time_s, u_px, v_px, w_px"
  for k in $(seq 1 10); do
    echo "0.$((k - 1))1, 320, 300, 20"
    if ((k == 2)); then echo "0.$((k - 1))1, 500, 300, 20"; fi
  done
} > "$tmp/detections.csv"
status=0
expect() {  # expected_removed flags...
  local expected="$1"
  shift
  "$bin" --detections "$tmp/detections.csv" --camera "$tmp/camera.csv" --initial-state "$tmp/initial.csv" \
    --association nn --svg-prefix "" --json "$@" > "$tmp/out.json"
  for pipeline in with_width without_width width_first_sight; do
    read -r added removed < <(python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))[sys.argv[2]]; print(r["added"], r["removed"])' \
      "$tmp/out.json" "$pipeline")
    echo "unconfirmed_check: ${*:-default}, $pipeline: $added trees added, $removed removed"
    if [[ "$added" != 2 || "$removed" != "$expected" ]]; then
      echo "unconfirmed_check: ${*:-default}, $pipeline: expected 2 trees added and $expected removed" >&2
      status=1
    fi
  done
}
expect 0
expect 1 --unconfirmed-after 3 --confirm-sightings 2
exit "$status"
