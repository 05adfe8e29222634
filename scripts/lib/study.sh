# shellcheck shell=bash
# Sourced by the scripts that run the tree-width study (examples/tree_width_study):
# scripts/run_study.sh, scripts/study_parallel.sh, scripts/study_slurm.sbatch,
# scripts/study_slurm_merge.sbatch and scripts/study_slurm_submit.sh. Functions only; their
# messages go to stderr. docs/study/cluster.md describes the sharded runs.

# sylva_study_build REPO BUILD JOBS: installs the Debian packages that are missing and builds
# tree_width_study (Release) in BUILD with JOBS jobs; the program is BUILD/bin/tree_width_study.
sylva_study_build() {
  local repo="$1" build="$2" jobs="$3"
  # shellcheck source=lib/install_packages.sh
  source "$repo/scripts/lib/install_packages.sh"
  sylva_install_packages build-essential cmake libeigen3-dev libboost-math-dev libcli11-dev nlohmann-json3-dev gnuplot-nox
  echo "==> building tree_width_study in $build" >&2
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSYLVA_NATIVE=OFF \
    -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_BENCHMARKS=OFF -DSYLVA_BUILD_EXAMPLES=ON \
    -DCMAKE_RUNTIME_OUTPUT_DIRECTORY="$build/bin" >&2
  cmake --build "$build" --target tree_width_study -j "$jobs" >&2
}

# sylva_study_parse_args FLAG...: sorts the study flags given to a sharding script. Sets
#   study_args     the flags every shard gets (--quick, --seed, --limit, --frames, --nees-every)
#   study_threads  --threads: threads per shard (default: $study_default_threads if set, else 1)
#   study_out      --out: the merged run file ("" if not given)
#   study_docs     --docs: where the report goes (default: $repo/docs)
#   study_quick    1 with --quick
#   study_seed     --seed (default 1)
#   study_report   0 with --no-report, --limit or --frames (the program itself writes no
#                  report for cut-short runs either), else 1
# --shard, merge and report are refused: the scripts choose the shards themselves. Needs $repo.
sylva_study_parse_args() {
  study_args=()
  study_threads="${study_default_threads:-1}"
  study_out=""
  study_docs="$repo/docs"
  study_quick=0
  study_seed=1
  study_report=1
  local arg name value
  while (($#)); do
    arg="$1"
    shift
    name="${arg%%=*}"
    case "$name" in
      --threads | --out | --docs | --seed | --limit | --frames | --nees-every)
        if [[ "$arg" == *=* ]]; then
          value="${arg#*=}"
        else
          (($#)) || { echo "$name needs a value" >&2; return 2; }
          value="$1"
          shift
        fi
        case "$name" in
          --threads) study_threads="$value" ;;
          --out) study_out="$value" ;;
          --docs) study_docs="$value" ;;
          *)
            study_args+=("$name" "$value")
            if [[ "$name" == --seed ]]; then study_seed="$value"; fi
            if [[ "$name" == --limit || "$name" == --frames ]] && [[ "$value" != 0 ]]; then
              study_report=0
            fi
            ;;
        esac
        ;;
      --quick)
        study_quick=1
        study_args+=(--quick)
        ;;
      --no-report) study_report=0 ;;
      --shard)
        echo "--shard: the script sets each shard's --shard K/N itself" >&2
        return 2
        ;;
      merge | report)
        echo "'$arg': run examples/tree_width_study's $arg subcommand directly" >&2
        return 2
        ;;
      *) study_args+=("$arg") ;;
    esac
  done
  [[ "$study_threads" =~ ^[1-9][0-9]*$ ]] || {
    echo "--threads: expected a positive number, got '$study_threads'" >&2
    return 2
  }
}

# sylva_study_part DIR K N: the run file of shard K of N.
sylva_study_part() { printf '%s/part_%s_of_%s.jsonl' "$1" "$2" "$3"; }

# sylva_study_infer_shards DIR: the N of the part_K_of_N.jsonl files in DIR (fails unless
# there is exactly one).
sylva_study_infer_shards() {
  local dir="$1" file ns=()
  for file in "$dir"/part_*_of_*.jsonl; do
    [[ -e "$file" ]] || continue
    file="${file##*_of_}"
    ns+=("${file%.jsonl}")
  done
  mapfile -t ns < <(printf '%s\n' "${ns[@]}" | sort -un | sed '/^$/d')
  if ((${#ns[@]} != 1)); then
    echo "cannot tell the number of shards from $dir/part_*_of_*.jsonl (found: ${ns[*]:-none});" \
      "set SYLVA_STUDY_SHARDS" >&2
    return 1
  fi
  echo "${ns[0]}"
}

# sylva_study_merge_report STUDY N DIR COMMAND: merges the N shards' run files in DIR into
# $study_out (default DIR/runs.jsonl) and, unless study_report is 0, writes the report
# (docs/results.md, docs/study/summary.csv, docs/images/study_*.svg under $study_docs)
# quoting COMMAND as the way to regenerate it. Call sylva_study_parse_args first.
sylva_study_merge_report() {
  local study="$1" n="$2" dir="$3" command="$4" k part parts=()
  for ((k = 1; k <= n; ++k)); do
    part="$(sylva_study_part "$dir" "$k" "$n")"
    [[ -f "$part" ]] || { echo "shard $k of $n is missing: $part" >&2; return 1; }
    parts+=("$part")
  done
  local out="${study_out:-$dir/runs.jsonl}"
  echo "==> merging $n shards into $out" >&2
  "$study" merge --out "$out" "${parts[@]}"
  if ((study_report)); then
    local plan=full
    if ((study_quick)); then plan=quick; fi
    echo "==> report into $study_docs" >&2
    "$study" --docs "$study_docs" --seed "$study_seed" \
      report --plan "$plan" --command "$command" "$out"
  fi
}

# sylva_study_command SCRIPT: the command results.md quotes, e.g. "bash
# scripts/study_parallel.sh --quick" (the sweep's flags only, like the program's own).
sylva_study_command() {
  local command="bash $1"
  if ((study_quick)); then command+=" --quick"; fi
  if [[ "$study_seed" != 1 ]]; then command+=" --seed $study_seed"; fi
  echo "$command"
}
