#!/usr/bin/env bash
# Fuzzes sylva's file loaders with libFuzzer (fuzz/README.md): builds every target of fuzz/
# with clang++ -fsanitize=fuzzer,address,undefined, runs them one after the other from the
# committed seeds (fuzz/corpus/<target>/ and fuzz/findings/<target>/, copied to a working
# corpus outside the repository), writes a JSON summary and regenerates the generated block
# of docs/reliability.md from it (scripts/fuzz_report.py).
#
#   bash scripts/fuzz.sh                    every target for 1,000,000 executions (the default)
#   bash scripts/fuzz.sh --runs N           N executions per target (per job with --jobs)
#   bash scripts/fuzz.sh --seconds S        S seconds per target (with --runs: what ends first)
#   bash scripts/fuzz.sh --jobs J           J fuzzing processes per target at a time (default 1)
#   bash scripts/fuzz.sh --targets a,b      only these (numeric_table, utias_mrclam,
#                                           victoria_park, leg_tracker, trunk_detections)
#   bash scripts/fuzz.sh --keep-corpus      go on from the working corpus of the last run
#   bash scripts/fuzz.sh --no-doc           write the summary, leave docs/reliability.md alone
#
# Missing Debian packages are installed with apt-get (as root, or through sudo).
# Environment: SYLVA_BUILD_ROOT (default <repo>/build): everything goes to its fuzz/ folder
# (bin/, work/<target>/{corpus,artifacts,logs}/, summary.json); SYLVA_FUZZ_CXX (default
# clang++) compiles the targets.
# A finding (a crash, a sanitizer report, a leak, a timeout, an exception other than
# sylva::Error) is saved by libFuzzer in work/<target>/artifacts/; the script then exits 1.
# Once the bug is fixed, copy the input to fuzz/findings/<target>/ so that ctest replays it.
set -euo pipefail

usage() { sed -n '2,23p' "$0" | sed 's/^# \{0,1\}//'; }

all_targets=(numeric_table utias_mrclam victoria_park leg_tracker trunk_detections)
targets=("${all_targets[@]}")
runs=""
seconds=""
jobs=1
keep_corpus=0
write_doc=1
command_line="bash scripts/fuzz.sh${*:+ $*}"
while (($#)); do
  case "$1" in
    --runs) runs="${2:?--runs needs a number}"; shift ;;
    --seconds) seconds="${2:?--seconds needs a number}"; shift ;;
    --jobs) jobs="${2:?--jobs needs a number}"; shift ;;
    --targets) IFS=, read -r -a targets <<<"${2:?--targets needs a list}"; shift ;;
    --keep-corpus) keep_corpus=1 ;;
    --no-doc) write_doc=0 ;;
    -h | --help) usage; exit 0 ;;
    *) echo "fuzz.sh: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
  shift
done
for n in $runs $seconds $jobs; do
  [[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz.sh: '$n' is not a positive whole number" >&2; exit 2; }
done
for t in "${targets[@]}"; do
  [[ " ${all_targets[*]} " == *" $t "* ]] || { echo "fuzz.sh: no target '$t' (${all_targets[*]})" >&2; exit 2; }
done
[[ -z "$runs" && -z "$seconds" ]] && runs=1000000

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SYLVA_BUILD_ROOT:-$repo/build}/fuzz"
cxx="${SYLVA_FUZZ_CXX:-clang++}"

# ---- dependencies ------------------------------------------------------------------------
# libFuzzer and the sanitizer runtimes come with clang's compiler-rt.
packages=(libeigen3-dev python3 pkg-config)
[[ -z "${SYLVA_FUZZ_CXX:-}" ]] && packages+=(clang libclang-rt-dev)
# shellcheck source=lib/install_packages.sh
source "$repo/scripts/lib/install_packages.sh"
sylva_install_packages "${packages[@]}"

# ---- build -------------------------------------------------------------------------------
cxxflags=(-std=c++17 -g -O1 -fno-omit-frame-pointer -fsanitize=fuzzer,address,undefined
          -fno-sanitize-recover=all -D_GLIBCXX_ASSERTIONS -Wall -Wextra -Wpedantic -Wshadow
          -I"$repo/include")
read -r -a eigen_flags <<<"$(pkg-config --cflags eigen3)"
mkdir -p "$build/bin"
for t in "${targets[@]}"; do
  echo "==> building $build/bin/$t" >&2
  "$cxx" "${cxxflags[@]}" "${eigen_flags[@]}" "$repo/fuzz/$t.cpp" -o "$build/bin/$t"
done

# ---- run, one target at a time -------------------------------------------------------------
fuzz_flags=(-print_final_stats=1 -timeout=10 -rss_limit_mb=2048 -dict="$repo/fuzz/loaders.dict")
[[ -n "$runs" ]] && fuzz_flags+=(-runs="$runs")
[[ -n "$seconds" ]] && fuzz_flags+=(-max_total_time="$seconds")
((jobs > 1)) && fuzz_flags+=(-jobs="$jobs" -workers="$jobs")
for t in "${targets[@]}"; do
  work="$build/work/$t"
  ((keep_corpus)) || rm -rf "$work/corpus"
  rm -rf "$work/artifacts" "$work/logs"
  mkdir -p "$work/corpus" "$work/artifacts" "$work/logs"
  for seeds in "$repo/fuzz/corpus/$t" "$repo/fuzz/findings/$t"; do
    [[ -d "$seeds" ]] && find "$seeds" -maxdepth 1 -type f -exec cp {} "$work/corpus/" \;
  done
  ls "$work/corpus" | wc -l >"$work/seed_count"
  echo "==> fuzzing $t: $build/bin/$t ${fuzz_flags[*]} (log: $work/logs/)" >&2
  start=$SECONDS
  rc=0
  if ((jobs > 1)); then  # libFuzzer writes fuzz-<job>.log into the current folder
    (cd "$work/logs" && "$build/bin/$t" "${fuzz_flags[@]}" -artifact_prefix="$work/artifacts/" "$work/corpus") || rc=$?
  else
    "$build/bin/$t" "${fuzz_flags[@]}" -artifact_prefix="$work/artifacts/" "$work/corpus" \
      2>"$work/logs/fuzz-0.log" || rc=$?
  fi
  echo "$rc" >"$work/exit_code"
  echo "$((SECONDS - start))" >"$work/seconds"
  grep -h -E '^#[0-9]+[[:space:]]+DONE|^Done [0-9]+ runs|ERROR|SUMMARY' "$work/logs/"fuzz-*.log >&2 || true
done

# ---- summary and report --------------------------------------------------------------------
summary="$build/summary.json"
python3 "$repo/scripts/fuzz_report.py" collect --work "$build/work" --targets "$(IFS=,; echo "${targets[*]}")" \
  --command="$command_line" --cxx="$cxx" --cxxflags="${cxxflags[*]//"$repo"/<repo>}" \
  --fuzz-flags="${fuzz_flags[*]//"$repo"/<repo>}" --repo="$repo" >"$summary"
echo "==> wrote $summary" >&2
if ((write_doc)); then
  python3 "$repo/scripts/fuzz_report.py" render "$summary" "$repo/docs/reliability.md"
  echo "==> regenerated the fuzz block of $repo/docs/reliability.md" >&2
fi
findings="$(python3 -c 'import json,sys; print(sum(t["findings"] for t in json.load(open(sys.argv[1]))["targets"]))' "$summary")"
if ((findings > 0)); then
  echo "==> $findings finding(s): see $build/work/<target>/artifacts/ and the logs" >&2
  exit 1
fi
echo "==> no finding" >&2
