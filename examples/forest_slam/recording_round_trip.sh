#!/usr/bin/env bash
# forest_slam's recording round trip (ctest forest_slam:recording_round_trip): the simulator
# writes its detections, camera and initial state as CSV (--write-recording), forest_slam reads
# them back (--detections), and every pipeline's estimate (trajectory and map CSV, 17
# significant digits) must be byte-identical to the run on the simulator's own data, with the
# ids (--association ids) and without them (--association nn).
# Usage: recording_round_trip.sh FOREST_SLAM_BINARY [FRAMES]
set -euo pipefail
bin="$1"
frames="${2:-300}"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/forest_round_trip.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
for association in ids nn; do
  "$bin" --frames "$frames" --svg-prefix "" --association "$association" --write-recording "$tmp/rec" \
    --csv-prefix "$tmp/sim_$association" --json > "$tmp/sim_$association.json"
  "$bin" --frames "$frames" --svg-prefix "" --association "$association" --detections "$tmp/rec_detections.csv" \
    --camera "$tmp/rec_camera.csv" --initial-state "$tmp/rec_initial_state.csv" --csv-prefix "$tmp/file_$association" \
    --json > "$tmp/file_$association.json"
  for pipeline in with_width without_width width_first_sight; do
    for what in trajectory map; do
      a="$tmp/sim_${association}_${pipeline}_${what}.csv"
      b="$tmp/file_${association}_${pipeline}_${what}.csv"
      if ! cmp -s "$a" "$b"; then
        echo "recording_round_trip: $association, $pipeline: the $what read back from the recording differs" >&2
        diff "$a" "$b" | head -5 >&2
        exit 1
      fi
    done
    rows=$(grep -vc '^#' "$tmp/sim_${association}_${pipeline}_trajectory.csv")
    if [[ "$rows" != "$frames" ]]; then
      echo "recording_round_trip: expected $frames trajectory rows, got $rows" >&2
      exit 1
    fi
  done
done
echo "recording_round_trip: $frames frames, ids and nn, three pipelines: estimates identical"
