#!/usr/bin/env bash
# Measures what the Python layer costs and writes docs/python.figures.json, which
# docs/python.md quotes (python/benchmarks/overhead.py says what is measured).
#
#   bash scripts/python_report.sh [--bin-dir DIR]
#
# The package is installed the way docs/python.md tells a user to (pip, g++ at setup.py's
# -O2, baseline instruction set) into $SYLVA_BUILD_ROOT/python-venv (default
# <repo>/build/python-venv). --bin-dir: a build's examples directory, for the comparison of
# the Python study with range_bearing_slam (regenerate_docs.sh passes its own).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin_args=()
while (($#)); do
  case "$1" in
    --bin-dir) bin_args=(--bin-dir "$(cd "$2" && pwd)"); shift ;;
    -h | --help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "python_report.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done
# shellcheck source=lib/install_packages.sh
source "$repo/scripts/lib/install_packages.sh"
# shellcheck source=lib/python_package.sh
source "$repo/scripts/lib/python_package.sh"
sylva_install_packages build-essential libeigen3-dev libboost-math-dev "${sylva_python_packages[@]}"
venv="${SYLVA_BUILD_ROOT:-$repo/build}/python-venv"
sylva_python_package "$venv"
"$venv/bin/python" "$repo/python/benchmarks/overhead.py" "${bin_args[@]}"
