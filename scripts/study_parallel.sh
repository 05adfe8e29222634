#!/usr/bin/env bash
# The tree-width study (examples/tree_width_study) in shards run by GNU parallel, on this
# machine or on several: shard K of N is `tree_width_study --shard K/N`; the shards' run files
# are merged into one, and the report goes into docs/ as with scripts/run_study.sh. For one
# build, the merged file is byte-identical to the single-process one (docs/study/cluster.md).
#
#   bash scripts/study_parallel.sh --quick         the reduced sweep, one shard per core here
#   bash scripts/study_parallel.sh --shards 48 --sshloginfile hosts
#                                                  the full study on the machines in hosts
#
# Options of this script (every other flag goes to each shard: --quick, --seed S, --limit N,
# --frames N, --nees-every N; --no-report leaves out the report):
#   --shards N        number of shards (default: this machine's cores)
#   --jobs J          shards at once on each machine (default: its cores / --threads)
#   --threads T       threads of each shard (default 1)
#   --sshloginfile F  run the shards on the machines listed in F (GNU parallel's option; ":"
#                     is this one); each must see the repository and --dir at the same path
#   --dir D           the shards' run files and logs (default <build>/study_shards)
#   --out F           the merged run file (default D/runs.jsonl)
#   --docs D          where the report goes (default <repo>/docs)
#
# Environment: SYLVA_STUDY_BIN, a tree_width_study built beforehand; without it the program
# is built in <build> = ${SYLVA_BUILD_ROOT:-<repo>/build}/main as run_study.sh does
# (SYLVA_JOBS: build parallelism). A missing GNU parallel is installed with apt-get.
set -euo pipefail

usage() { sed -n '2,24p' "$0" | sed 's/^# \{0,1\}//'; }
die() { echo "study_parallel.sh: $*" >&2; exit 2; }

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SYLVA_BUILD_ROOT:-$repo/build}/main"
# shellcheck source=lib/study.sh
source "$repo/scripts/lib/study.sh"

shards="$(nproc)"
jobs=""
sshloginfile=""
dir="$build/study_shards"
rest=()
while (($#)); do
  arg="$1"
  shift
  case "$arg" in
    --shards=* | --jobs=* | --sshloginfile=* | --dir=*) set -- "${arg%%=*}" "${arg#*=}" "$@" ;;
    --shards | --jobs | --sshloginfile | --dir)
      (($#)) || die "$arg needs a value"
      case "$arg" in
        --shards) shards="$1" ;;
        --jobs) jobs="$1" ;;
        --sshloginfile) sshloginfile="$1" ;;
        --dir) dir="$1" ;;
      esac
      shift
      ;;
    -h | --help) usage && exit 0 ;;
    *) rest+=("$arg") ;;
  esac
done
sylva_study_parse_args "${rest[@]}"
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "--shards: expected a positive number, got '$shards'"
# GNU parallel takes a share of each machine's cores: 50% for two threads per shard.
[[ -n "$jobs" ]] || jobs="$((study_threads < 100 ? 100 / study_threads : 1))%"

if [[ -n "${SYLVA_STUDY_BIN:-}" ]]; then
  study="$SYLVA_STUDY_BIN"
  [[ -x "$study" ]] || die "SYLVA_STUDY_BIN=$study is not an executable"
else
  sylva_study_build "$repo" "$build" "${SYLVA_JOBS:-$(nproc)}"
  study="$build/bin/tree_width_study"
fi
if ! command -v parallel >/dev/null; then
  # shellcheck source=lib/install_packages.sh
  source "$repo/scripts/lib/install_packages.sh"
  sylva_install_packages parallel
fi

# Absolute paths: the command line also has to work in another machine's login shell.
study="$(cd "$(dirname "$study")" && pwd)/$(basename "$study")"
mkdir -p "$dir"
dir="$(cd "$dir" && pwd)"
rm -f "$dir"/part_*_of_*.jsonl "$dir"/part_*_of_*.log "$dir/joblog.tsv"

# One shell command line with {} for the shard index, each argument quoted.
printf -v command '%q ' "$study" "${study_args[@]}" --no-report --threads "$study_threads"
part="$(sylva_study_part "$(printf '%q' "$dir")" '{}' "$shards")"
command+="--shard {}/$shards --out $part 2> ${part%.jsonl}.log && echo \"==> shard {}/$shards done\" >&2"

par=(parallel --jobs "$jobs" --halt "now,fail=1" --joblog "$dir/joblog.tsv")
if [[ -n "$sshloginfile" ]]; then par+=(--sshloginfile "$sshloginfile"); fi
mapfile -t indices < <(seq 1 "$shards")
echo "==> $shards shards of $study (GNU parallel --jobs $jobs${sshloginfile:+ on the machines in $sshloginfile}," \
  "$study_threads thread(s) per shard); logs in $dir/part_K_of_$shards.log" >&2
if ! "${par[@]}" "$command" ::: "${indices[@]}"; then
  echo "study_parallel.sh: a shard failed (GNU parallel's job log: $dir/joblog.tsv)" >&2
  # Column 7 of the job log is the exit status, 8 the signal (the shards stopped by --halt).
  while read -r k; do
    log="$(sylva_study_part "$dir" "$k" "$shards")"
    log="${log%.jsonl}.log"
    echo "--- $log (last lines)" >&2
    tail -n 5 "$log" >&2 || true
  done < <(awk -F'\t' 'NR > 1 && $7 != 0 && $8 == 0 { print $1 }' "$dir/joblog.tsv")
  exit 1
fi

sylva_study_merge_report "$study" "$shards" "$dir" "$(sylva_study_command scripts/study_parallel.sh)"
echo "==> done in $((SECONDS / 60)) min $((SECONDS % 60)) s" >&2
