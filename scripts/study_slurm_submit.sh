#!/usr/bin/env bash
# Submits the tree-width study to Slurm from a login node: builds examples/tree_width_study
# here as scripts/run_study.sh does (the compute nodes run this build, so the repository must
# be on a file system they share), submits scripts/study_slurm.sbatch as an array of N tasks,
# one shard each, and scripts/study_slurm_merge.sbatch to merge and report once every task has
# succeeded (sbatch --dependency=afterok:<array job id>).
#
#   bash scripts/study_slurm_submit.sh --quick
#   bash scripts/study_slurm_submit.sh --shards 64 --sbatch --partition=long
#   bash scripts/study_slurm_submit.sh --build-only
#
# Options of this script (every other flag goes to the shards and the report: --quick,
# --seed S, --threads T (also the tasks' --cpus-per-task), --no-report, --docs D, ...):
#   --shards N      the array's size and number of shards (default 16)
#   --sbatch OPT    one more option for both sbatch calls, e.g. --sbatch --account=abc
#                   (repeat it for more); the array's own --time etc. win over the #SBATCH lines
#   --dir D         the shards' run files and the jobs' logs (default <build>/study_shards)
#   --build-only    build the program and stop
#
# Environment: SYLVA_STUDY_BIN (a program built beforehand: nothing is built),
# SYLVA_BUILD_ROOT (<build> is ${SYLVA_BUILD_ROOT:-<repo>/build}/main), SYLVA_JOBS (build
# parallelism). docs/study/cluster.md has the steps by hand and what to do when a task fails.
set -euo pipefail

usage() { sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; }
die() { echo "study_slurm_submit.sh: $*" >&2; exit 2; }

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SYLVA_BUILD_ROOT:-$repo/build}/main"
# shellcheck source=lib/study.sh
source "$repo/scripts/lib/study.sh"

shards=16
dir="$build/study_shards"
build_only=0
sbatch_args=()
rest=()
while (($#)); do
  arg="$1"
  shift
  case "$arg" in
    --shards=* | --dir=*) set -- "${arg%%=*}" "${arg#*=}" "$@" ;;
    --sbatch=*) sbatch_args+=("${arg#*=}") ;;
    --shards | --dir | --sbatch)
      (($#)) || die "$arg needs a value"
      case "$arg" in
        --shards) shards="$1" ;;
        --dir) dir="$1" ;;
        --sbatch) sbatch_args+=("$1") ;;
      esac
      shift
      ;;
    --build-only) build_only=1 ;;
    -h | --help) usage && exit 0 ;;
    *) rest+=("$arg") ;;
  esac
done
sylva_study_parse_args "${rest[@]}"  # checks the flags before anything is built or submitted
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "--shards: expected a positive number, got '$shards'"
((build_only)) || command -v sbatch >/dev/null || die "sbatch not found: run this on a Slurm login node"

if [[ -n "${SYLVA_STUDY_BIN:-}" ]]; then
  study="$SYLVA_STUDY_BIN"
else
  sylva_study_build "$repo" "$build" "${SYLVA_JOBS:-$(nproc)}"
  study="$build/bin/tree_width_study"
fi
[[ -x "$study" ]] || die "$study is not an executable"
study="$(cd "$(dirname "$study")" && pwd)/$(basename "$study")"
if ((build_only)); then
  echo "==> built $study" >&2
  exit 0
fi

mkdir -p "$dir"
dir="$(cd "$dir" && pwd)"
rm -f "$dir"/part_*_of_*.jsonl
# The tasks find all they need in their environment (sbatch passes it on with --export=ALL).
export SYLVA_REPO="$repo" SYLVA_STUDY_BIN="$study" SYLVA_STUDY_DIR="$dir" SYLVA_STUDY_SHARDS="$shards"

array_job="$(sbatch --parsable --export=ALL --array="1-$shards" --cpus-per-task="$study_threads" \
  --output="$dir/tree_width_study_%A_%a.log" "${sbatch_args[@]}" \
  "$repo/scripts/study_slurm.sbatch" "${rest[@]}")"
array_job="${array_job%%;*}"  # --parsable prints "jobid" or "jobid;cluster"
merge_job="$(sbatch --parsable --export=ALL --dependency="afterok:$array_job" \
  --output="$dir/tree_width_study_%j_merge.log" "${sbatch_args[@]}" \
  "$repo/scripts/study_slurm_merge.sbatch" "${rest[@]}")"
merge_job="${merge_job%%;*}"
cat >&2 <<EOF
==> submitted the array job $array_job ($shards shards of $study) and the merge job $merge_job
    (it starts once every task has succeeded). Logs: $dir/tree_width_study_<job>_*.log
    Follow them with: squeue -u "\$USER"   and afterwards: sacct -j $array_job,$merge_job
EOF
echo "$array_job $merge_job"
