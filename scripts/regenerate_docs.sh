#!/usr/bin/env bash
# One command for every figure a reader sees in README.md and docs/.
#
#   bash scripts/regenerate_docs.sh            builds the examples (Release) and reruns the quick
#                                              figure sources: the example runs whose figures and
#                                              pictures README and the example pages quote
#                                              (scripts/docs_figures.py, SOURCES); writes their
#                                              figures files and pictures into docs/, rewrites every
#                                              quoted figure, and checks the pages (a few minutes);
#                                              builds the Python package and measures its cost
#                                              (scripts/python_report.sh, docs/python.md)
#   bash scripts/regenerate_docs.sh --pages    also reruns the generators of the long pages first:
#                                              the study (docs/results.md, about an hour on 2 cores),
#                                              consistency, forest seeds, real data, benchmarks,
#                                              the clean build
#   bash scripts/regenerate_docs.sh --quick    CI: runs each figure source in a reduced
#                                              configuration into a temporary folder, checks that it
#                                              gives the figures the pages quote (same names), and
#                                              checks the committed pages against the committed
#                                              figures files; changes nothing in docs/
#
# Options: --bin-dir DIR uses the examples of an existing build (its examples/ folder) instead
# of building them in $SYLVA_BUILD_ROOT/docs (default <repo>/build/docs).
# Pages say which figures come from here: a figure in prose is written
# <!--fig:SOURCE.KEY-->value<!--/fig-->, and `python3 scripts/docs_figures.py check` (the ctest
# docs_figures_check, label "docs") fails when it differs from the figures file.
set -euo pipefail

usage() { sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; }
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
quick=0
pages=0
bin_dir=""
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --pages) pages=1 ;;
    --bin-dir) bin_dir="$(cd "$2" && pwd)"; shift ;;
    -h | --help) usage; exit 0 ;;
    *) echo "regenerate_docs.sh: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
  shift
done

# shellcheck source=lib/install_packages.sh
source "$repo/scripts/lib/install_packages.sh"
if [[ -z "$bin_dir" ]]; then
  sylva_install_packages build-essential cmake libeigen3-dev libcli11-dev nlohmann-json3-dev libboost-math-dev libbenchmark-dev python3
  build="${SYLVA_BUILD_ROOT:-$repo/build}/docs"
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSYLVA_NATIVE=OFF \
    ${SYLVA_CXX:+-DCMAKE_CXX_COMPILER="$SYLVA_CXX"} \
    -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_BENCHMARKS=ON -DSYLVA_BUILD_EXAMPLES=ON >&2
  targets=(--target range_bearing_slam parking laser_camera_slam moving_objects forest_slam bench_slam_step)
  ((pages)) && targets=()  # forest_seeds runs forest_slam from this build too
  cmake --build "$build" -j "${SYLVA_JOBS:-$(nproc)}" "${targets[@]}" >&2
  bin_dir="$build/examples"
fi

figures=(python3 "$repo/scripts/docs_figures.py")
if ((quick)); then
  out="$(mktemp -d "${TMPDIR:-/tmp}/sylva-docs.XXXXXX")"
  trap 'rm -rf "$out"' EXIT
  "${figures[@]}" run --quick --bin-dir "$bin_dir" --out "$out"
  "${figures[@]}" check
  exit 0
fi

if ((pages)); then
  # The long generators, each of which writes its own page (and says so at its top).
  bash "$repo/scripts/run_study.sh" tune
  bash "$repo/scripts/run_study.sh"
  bash "$repo/scripts/consistency_report.sh"
  python3 "$repo/scripts/forest_slam_seeds.py" --build-dir "$(dirname "$bin_dir")"
  bash "$repo/scripts/real_data_report.sh"
  bash "$repo/scripts/run_benchmarks.sh"
  bash "$repo/scripts/clean_build_report.sh"
fi
"${figures[@]}" run --bin-dir "$bin_dir"
bash "$repo/scripts/python_report.sh" --bin-dir "$bin_dir"  # docs/python.figures.json
"${figures[@]}" update
"${figures[@]}" check
