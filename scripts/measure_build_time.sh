#!/usr/bin/env bash
# Measures how long the tests and examples take to build from a clean tree, per translation
# unit, and writes it as JSON for docs/clean-build.md (scripts/clean_build_report.sh calls this).
#
#   bash scripts/measure_build_time.sh [OUT_JSON]      (default: build/build-times.json)
#   bash scripts/measure_build_time.sh --tree REV [OUT_JSON]
#                                                      the same for the repository's tree at
#                                                      commit REV (git archive), built by this
#                                                      script: a reference for a comparison in
#                                                      the same sitting (clean_build_report.sh)
#
# A fresh Ninja build directory in a temporary folder, Release, tests and examples (the
# benchmarks are left out: they are what is being measured elsewhere), the default C++
# compiler (CXX overrides it), SYLVA_JOBS parallel jobs (default: number of cores). The JSON
# holds the wall time of the whole build, the compiler, the job count, and each object's
# compile time from Ninja's log. On a busy machine the per-object times are inflated alike;
# the wall time of a build with the machine to itself is the figure to quote.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tree=""
if [[ "${1:-}" == --tree ]]; then
  [[ -n "${2:-}" ]] || { echo "measure_build_time.sh: --tree needs a commit" >&2; exit 2; }
  tree="$(git -C "$repo" rev-parse --verify --quiet "$2^{commit}")" ||
    { echo "measure_build_time.sh: '$2' is not a commit of $repo" >&2; exit 2; }
  shift 2
fi
out="${1:-$repo/build/build-times.json}"
jobs="${SYLVA_JOBS:-$(nproc)}"
command -v ninja > /dev/null || { echo "measure_build_time.sh: needs ninja (apt-get install ninja-build)" >&2; exit 2; }

work="$(mktemp -d "${TMPDIR:-/tmp}/sylva-build-time.XXXXXX")"
trap 'rm -rf "$work"' EXIT
source_dir="$repo"
tmp="$work/build"
mkdir -p "$tmp"
if [[ -n "$tree" ]]; then
  source_dir="$work/source"
  mkdir -p "$source_dir"
  git -C "$repo" archive "$tree" | tar -x -C "$source_dir"
fi
cmake -S "$source_dir" -B "$tmp" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSYLVA_NATIVE=OFF \
  -DSYLVA_BUILD_TESTS=ON -DSYLVA_BUILD_EXAMPLES=ON -DSYLVA_BUILD_BENCHMARKS=OFF > "$tmp/configure.log"
compiler="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$tmp/CMakeCache.txt")"
version="$("$compiler" --version | head -n 1)"
start=$(date +%s.%N)
ninja -C "$tmp" -j "$jobs" > "$tmp/build.log"
end=$(date +%s.%N)

mkdir -p "$(dirname "$out")"
python3 - "$tmp/.ninja_log" "$out" "$start" "$end" "$version" "$jobs" "$(nproc)" "${tree:-$(git -C "$repo" rev-parse HEAD 2> /dev/null || echo unknown)}" "$([[ -n "$tree" ]] && echo 1 || echo 0)" <<'PY'
import json, sys
log, out, start, end, version, jobs, cores, commit, archived = sys.argv[1:]
objects = []
with open(log, encoding="utf-8") as f:
    for line in f:
        if line.startswith("#"):
            continue
        begin_ms, end_ms, _, target, _ = line.rstrip("\n").split("\t")
        if target.endswith(".o"):
            objects.append({"object": target, "seconds": (int(end_ms) - int(begin_ms)) / 1000.0})
objects.sort(key=lambda o: -o["seconds"])
# "commit": the tree built (for the working tree: its HEAD, with whatever is not committed).
json.dump({"wall_seconds": float(end) - float(start), "compiler": version, "jobs": int(jobs),
           "cores": int(cores), "commit": commit, "archived_tree": archived == "1",
           "objects": objects}, open(out, "w"), indent=1)
print(f"build of tests and examples: {float(end) - float(start):.0f} s wall with {jobs} jobs ({version}); "
      f"{sum(o['seconds'] for o in objects):.0f} s of compiling in {len(objects)} objects -> {out}")
PY
