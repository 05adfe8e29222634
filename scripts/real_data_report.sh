#!/usr/bin/env bash
# Regenerates docs/results-real-data.md and its pictures (docs/images/victoria_park_*.svg,
# docs/images/utias_robot*.svg) from the real data sets in ../shared/data (or DATA_DIR):
#   1. a Release build with -march=native of examples/victoria_park and examples/utias in
#      BUILD_DIR (default build-real-data; clang++ when installed and CXX is not set, as for
#      the benchmarks: the Victoria Park run time is one of the issue's targets),
#   2. victoria_park --json --robustness (both variants, the 81-setting noise study on
#      THREADS threads) and utias --json, each writing its pictures into docs/images,
#   3. scripts/real_data_report.py, which writes the page from the two JSON files,
#   4. utias --leave-one-out --json and scripts/utias_report.py, which rewrite the generated
#      tables of docs/examples/utias.md (leave-one-robot-out, the grid's ranking, the results).
# The JSON stays in BUILD_DIR. The whole run takes a few minutes on 2 cores.
#
# Usage: bash scripts/real_data_report.sh [BUILD_DIR]
# Environment: DATA_DIR (default <repo>/../shared/data), THREADS (default 2), JOBS (default 2).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-${root}/build-real-data}"
data_dir="${DATA_DIR:-${root}/../shared/data}"
threads="${THREADS:-2}"
jobs="${JOBS:-2}"

for folder in victoria-park utias-mrclam/MRCLAM_Dataset7; do
  if [[ ! -d "${data_dir}/${folder}" ]]; then
    echo "real_data_report.sh: ${data_dir}/${folder} is missing; see docs/examples/victoria-park.md and" \
      "docs/examples/utias.md for where to get the data, and set DATA_DIR" >&2
    exit 1
  fi
done

# shellcheck source=lib/install_packages.sh
source "${root}/scripts/lib/install_packages.sh"
# shellcheck source=lib/prefer_clang.sh
source "${root}/scripts/lib/prefer_clang.sh"
sylva_install_packages build-essential cmake clang libeigen3-dev libcli11-dev nlohmann-json3-dev \
  libboost-math-dev python3

sylva_prefer_clang "${build_dir}"
cmake -S "${root}" -B "${build_dir}" -DCMAKE_BUILD_TYPE=Release -DSYLVA_NATIVE=ON \
  -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_BENCHMARKS=OFF -DSYLVA_BUILD_EXAMPLES=ON
cmake --build "${build_dir}" -j "${jobs}" --target victoria_park utias

compiler="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "${build_dir}/CMakeCache.txt")"
context="$("${compiler}" --version | head -n 1), -O3 -march=native; $(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1)"

cd "${root}"
commands="${build_dir}/commands.txt"
vp=(--data "${data_dir}/victoria-park" --json --robustness --threads "${threads}" --svg-prefix docs/images/victoria_park)
ut=(--data "${data_dir}/utias-mrclam/MRCLAM_Dataset7" --json --svg-prefix docs/images/utias)
# The page shows the commands with the data folder as the user passed it (default ../shared/data).
shown_data="${DATA_DIR:-../shared/data}"
printf '%s\n' "${build_dir#"${root}"/}/examples/victoria_park/victoria_park ${vp[*]}" \
  "${build_dir#"${root}"/}/examples/utias/utias ${ut[*]}" | sed "s|${data_dir}|${shown_data}|g" > "${commands}"
echo "==> victoria_park" >&2
"${build_dir}/examples/victoria_park/victoria_park" "${vp[@]}" > "${build_dir}/victoria_park.json"
echo "==> utias" >&2
"${build_dir}/examples/utias/utias" "${ut[@]}" > "${build_dir}/utias.json"
echo "==> utias --leave-one-out" >&2
"${build_dir}/examples/utias/utias" --data "${data_dir}/utias-mrclam/MRCLAM_Dataset7" --leave-one-out --json \
  > "${build_dir}/utias_loro.json"
python3 "${root}/scripts/real_data_report.py" --victoria-park "${build_dir}/victoria_park.json" \
  --utias "${build_dir}/utias.json" --loro "${build_dir}/utias_loro.json" --commands "${commands}" \
  --context "${context}" --out "${root}/docs/results-real-data.md"
echo "==> wrote docs/results-real-data.md" >&2
echo "==> utias with the fixed calibration, and with gains learned from scratch" >&2
"${build_dir}/examples/utias/utias" --data "${data_dir}/utias-mrclam/MRCLAM_Dataset7" --leave-one-out --gains fixed \
  --json > "${build_dir}/utias_loro_fixed.json"
"${build_dir}/examples/utias/utias" --data "${data_dir}/utias-mrclam/MRCLAM_Dataset7" --v-gain 1 --omega-gain 1 \
  --omega-bias 0 --gain-sigma 0.1 0.1 0.01 --json > "${build_dir}/utias_scratch.json"
python3 "${root}/scripts/utias_report.py" --run "${build_dir}/utias.json" --loro "${build_dir}/utias_loro.json" \
  --loro-fixed "${build_dir}/utias_loro_fixed.json" --run-scratch "${build_dir}/utias_scratch.json" \
  --doc "${root}/docs/examples/utias.md"
echo "==> updated the generated tables of docs/examples/utias.md" >&2
