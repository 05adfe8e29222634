#!/usr/bin/env bash
# forest_slam's loop test without ids (ctest forest_slam:loop): pairings that the continuity
# test refuses one at a time, with trees of at least --loop-sightings sightings, are taken
# together when at least --loop-pairings of them are jointly compatible.
# A still camera sees three trunks (u = 200, 320, 440) for 40 frames, then in frame 41 only a
# fourth (u = 560), then from frame 42 to 45 the first three again ("three") or only two of
# them ("two"). The continuity test is made to refuse every pairing it judges (--continuity-cost
# 0), so each trunk seen again after frame 41 is judged and refused on its own:
#   - three, the loop test on (3 pairings, 30 sightings): the three are taken together, and no
#     tree is started after frame 41: 4 trees;
#   - three, the loop test off (--loop-pairings 0): each starts a tree of its own: 7;
#   - two: fewer than 3 pairings, so they start trees either way: 6;
#   - three with --loop-sightings 50: the trees have taken too few sightings: 7.
# Checked for the three pipelines.
# Usage: loop_check.sh FOREST_SLAM_BINARY
set -euo pipefail
bin="$1"
# shellcheck source=still_camera.sh
source "$(dirname "${BASH_SOURCE[0]}")/still_camera.sh" forest_loop
write() {  # file, the trunks (u) of frames 42-45
  {
    echo "# time_s, u_px, v_px, w_px"
    for k in $(seq 1 45); do
      t=$(awk -v k="$k" 'BEGIN { printf "%.2f", 0.1 * k }')
      if ((k <= 40)); then for u in 200 320 440; do echo "$t, $u, 300, 20"; done
      elif ((k == 41)); then echo "$t, 560, 300, 20"
      else for u in $2; do echo "$t, $u, 300, 20"; done
      fi
    done
  } > "$tmp/$1.csv"
}
write three "200 320 440"
write two "200 320"
status=0
expect() {  # case, expected trees, forest_slam flags...
  local case="$1" expected="$2"
  shift 2
  "$bin" --detections "$tmp/$case.csv" --camera "$tmp/camera.csv" --initial-state "$tmp/initial.csv" \
    --association nn --continuity-cost 0 --svg-prefix "" --json "$@" > "$tmp/out.json"
  expect_trees_added loop_check "$case $*" "$expected" "$tmp/out.json" || status=1
}
expect three 4
expect three 7 --loop-pairings 0
expect two 6
expect three 7 --loop-sightings 50
exit "$status"
