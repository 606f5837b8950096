#!/usr/bin/env bash
# Runs a rollbench study on a SLURM cluster: a job array of N shards
# (`rollbench run ... --shard i/N`), then one job that merges the shard
# reports and plots them, started when every shard has ended.
#
#   scripts/slurm/submit.sh --dir DIR [--shards N] [--partition P] [--account A]
#       [--time T] [--cpus C] [--only LIST] [--no-plot] [--wait] -- RUN-OPTIONS...
#
#   --dir DIR      the study's folder on storage every node sees: run-args,
#                  shards/shard-<i>.json, logs/, report.json, plots/
#   --shards N     how many array elements (default 4)
#   --partition, --account, --time (per job, e.g. 2:00:00), --cpus (per shard,
#                  also its --jobs): passed to sbatch; anything else sbatch
#                  reads from its SBATCH_* environment variables
#   --only LIST    resubmit only these shards (e.g. 1,3) of a study already in
#                  DIR with its run-args, then the merge again
#   --no-plot      merge only
#   --wait         stay until the merge has ended, printing progress, and exit
#                  with the merge job's status (sbatch --wait)
#   RUN-OPTIONS    what `rollbench run` gets besides --shard and --out
#
# Environment: ROLLBENCH, the binary every node runs (default: this
# checkout's build/release/rollbench; it must be on shared storage).
set -euo pipefail
source_dir="$(cd "$(dirname "$0")/../.." && pwd)"
here="$source_dir/scripts/slurm"
usage() { sed -n '6,20p' "$0" | sed 's/^# \{0,1\}//'; exit "$1"; }
die() { echo "submit: $*" >&2; exit 2; }

dir="" shards=4 only="" plot=1 wait=0 sbatch_opts=()
while [ $# -gt 0 ]; do
  case "$1" in
    --dir) dir="${2:?--dir needs a folder}"; shift 2 ;;
    --shards) shards="${2:?--shards needs a number}"; shift 2 ;;
    --partition | --account | --time) sbatch_opts+=("$1=${2:?$1 needs a value}"); shift 2 ;;
    --cpus) sbatch_opts+=("--cpus-per-task=${2:?--cpus needs a number}"); shift 2 ;;
    --only) only="${2:?--only needs shard numbers, e.g. 1,3}"; shift 2 ;;
    --no-plot) plot=0; shift ;;
    --wait) wait=1; shift ;;
    --) shift; break ;;
    -h | --help) usage 0 ;;
    *) die "unknown option '$1' (rollbench's options go after --)" ;;
  esac
done
[ -n "$dir" ] || die "--dir is required: the study's folder on shared storage"
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "--shards: expected a whole number >= 1, got '$shards'"
rollbench="$(realpath "${ROLLBENCH:-$source_dir/build/release/rollbench}")"
[ -x "$rollbench" ] || die "no rollbench binary at $rollbench (build it, or set ROLLBENCH)"
mkdir -p "$dir/shards" "$dir/logs"
dir="$(cd "$dir" && pwd)"

if [ -n "$only" ]; then
  [ $# -eq 0 ] || die "--only reruns shards of the study in $dir with its own options: give no RUN-OPTIONS"
  [ -f "$dir/run-args" ] && [ -f "$dir/shard-count" ] || die "--only: no study in $dir (run-args, shard-count)"
  shards="$(cat "$dir/shard-count")"
  array="$only"
  for i in ${only//,/ }; do
    [[ "$i" =~ ^[0-9]+$ ]] && [ "$i" -lt "$shards" ] || die "--only: '$i' is not a shard of 0..$((shards - 1))"
  done
else
  [ $# -gt 0 ] || die "no RUN-OPTIONS after --: say what to run (e.g. -- --preset full)"
  for arg in "$@"; do
    case "$arg" in --shard | --shard=* | --out | --out=*) die "RUN-OPTIONS: leave $arg out: each shard gets its own" ;; esac
  done
  printf '%s\n' "$@" > "$dir/run-args"
  echo "$shards" > "$dir/shard-count"
  rm -f "$dir"/shards/shard-*.json "$dir/report.json"
  array="0-$((shards - 1))"
fi

export RB_STUDY_DIR="$dir" RB_SHARDS="$shards" RB_ROLLBENCH="$rollbench" RB_SOURCE="$source_dir" RB_PLOT="$plot"
array_job=$(sbatch --parsable "${sbatch_opts[@]}" --array="$array" --chdir="$dir" \
  --output="$dir/logs/shard-%a.log" --export=ALL "$here/shard.sbatch")
array_job="${array_job%%;*}"
echo "submit: shards $array of $shards: job array $array_job"
# afterany, not afterok: the merge runs even when a shard failed, so that it
# says which shards are missing instead of waiting forever on a dependency
# that can never be met
merge_opts=("${sbatch_opts[@]}" --dependency="afterany:$array_job" --chdir="$dir"
  --output="$dir/logs/merge.log" --export=ALL "$here/merge.sbatch")
if [ "$wait" = 0 ]; then
  merge_job=$(sbatch --parsable "${merge_opts[@]}")
  echo "submit: merge and plot: job ${merge_job%%;*} (after $array_job); results in $dir"
  exit 0
fi
# --wait: sbatch returns when the merge has ended, with its exit status;
# meanwhile, a line of progress every few seconds
sbatch --wait --quiet "${merge_opts[@]}" &
waiter=$!
"$here/progress.sh" "$array_job" "$shards" "$dir" "$waiter"
rc=0
wait "$waiter" || rc=$?
echo "submit: merge job ended with status $rc; logs in $dir/logs"
[ "$rc" -ne 0 ] || echo "submit: report $dir/report.json$([ "$plot" = 0 ] || echo ", plots $dir/plots/")"
exit "$rc"
