#!/usr/bin/env bash
# forest_slam's continuity test without ids (ctest forest_slam:continuity): where it applies.
# A still camera, with the test made to refuse every pairing it judges (--continuity-cost 0)
# and with the test off (inf):
#   - centre: one trunk at the image's centre for ten frames. A tree sighted in the previous
#     frame, away from the edges, continues on the gate alone: one tree either way.
#   - edge: the same trunk 2 px from the left edge (u = 12, w = 20), within the default 15 px
#     margin: every frame is judged, so a cost of 0 starts a tree each frame (ten); off, one.
#   - gap: the centre trunk in frames 1-5 and 8-10, and another trunk in frames 6-7 only. After
#     its gap the first tree is judged: three trees at a cost of 0, two with the test off.
# Checked for the three pipelines.
# Usage: continuity_check.sh FOREST_SLAM_BINARY
set -euo pipefail
bin="$1"
# shellcheck source=still_camera.sh
source "$(dirname "${BASH_SOURCE[0]}")/still_camera.sh" forest_continuity
header="# time_s, u_px, v_px, w_px"
{ echo "$header"; for k in $(seq 1 10); do echo "0.$((k - 1))1, 320, 300, 20"; done; } > "$tmp/centre.csv"
{ echo "$header"; for k in $(seq 1 10); do echo "0.$((k - 1))1, 12, 300, 20"; done; } > "$tmp/edge.csv"
{
  echo "$header"
  for k in $(seq 1 10); do
    if ((k == 6 || k == 7)); then echo "0.$((k - 1))1, 500, 300, 20"; else echo "0.$((k - 1))1, 320, 300, 20"; fi
  done
} > "$tmp/gap.csv"
status=0
expect() {  # case cost expected
  "$bin" --detections "$tmp/$1.csv" --camera "$tmp/camera.csv" --initial-state "$tmp/initial.csv" \
    --association nn --continuity-cost "$2" --svg-prefix "" --json > "$tmp/out.json"
  expect_trees_added continuity_check "$1, cost $2" "$3" "$tmp/out.json" || status=1
}
expect centre inf 1
expect centre 0 1
expect edge inf 1
expect edge 0 10
expect gap inf 2
expect gap 0 3
exit "$status"
