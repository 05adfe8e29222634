# Shared by forest_slam's checks on hand-written detections. `source still_camera.sh NAME`
# makes a temporary folder $tmp (removed on exit) holding a still camera at the origin,
# $tmp/camera.csv and $tmp/initial.csv, and defines expect_trees_added: the number of trees a
# run added in each of the three pipelines.

# still_camera_files DIR: DIR/camera.csv (640 x 480, f = 500 px) and DIR/initial.csv (at rest at
# the origin, looking along z).
still_camera_files() {
  printf '# fx_px, fy_px, cx_px, cy_px, width_px, height_px\n500, 500, 320, 240, 640, 480\n' > "$1/camera.csv"
  printf '# r_WC (3), q_WC (w, x, y, z), v_W (3), omega_C (3)\n0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0\n' > "$1/initial.csv"
}

# expect_trees_added CHECK LABEL EXPECTED JSON: says how many trees each pipeline added in the
# forest_slam --json output JSON, and returns 1 if any is not EXPECTED.
expect_trees_added() {
  local check="$1" label="$2" expected="$3" json="$4" pipeline added failed=0
  for pipeline in with_width without_width width_first_sight; do
    added=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))[sys.argv[2]]["added"])' "$json" "$pipeline")
    echo "$check: $label, $pipeline: $added trees added"
    if [[ "$added" != "$expected" ]]; then
      echo "$check: $label, $pipeline: expected $expected trees" >&2
      failed=1
    fi
  done
  return "$failed"
}

tmp="$(mktemp -d "${TMPDIR:-/tmp}/$1.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
still_camera_files "$tmp"
