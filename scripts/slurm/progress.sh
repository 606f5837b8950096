#!/usr/bin/env bash
# Progress of a study while it runs: every few seconds one line with the time
# since submission, shards finished (their reports written) of all, how
# many are running or waiting in squeue, how many ended without a report, and
# an estimate of the time left at the pace of the shards done so far.
# Ends when process WAITER (the sbatch --wait of the merge) ends.
#   scripts/slurm/progress.sh ARRAY_JOB SHARDS DIR WAITER
set -euo pipefail
array_job="$1" shards="$2" dir="$3" waiter="$4"
interval="${RB_PROGRESS_SECONDS:-5}"
start=$SECONDS
last="" estimate=""
count_done() { find "$dir/shards" -maxdepth 1 -name 'shard-*.json' | wc -l; }
# a rerun (submit.sh --only) starts with the other shards done already
done_before=$(count_done)
while kill -0 "$waiter" 2>/dev/null; do
  done_count=$(count_done)
  states=$(squeue -h -r -j "$array_job" -o %t 2>/dev/null || true)
  running=$(grep -c '^R$' <<<"$states" || true)
  pending=$(grep -c '^PD$' <<<"$states" || true)
  failed=$((shards - done_count - running - pending))
  line="shards done $done_count/$shards, running $running, pending $pending"
  [ "$failed" -le 0 ] || line="$line, ended without a report $failed"
  elapsed=$((SECONDS - start))
  if [ "$running" -gt 0 ] || [ "$pending" -gt 0 ]; then
    # the shards so far set the pace: the same rate for the rest
    done_now=$((done_count - done_before))
    [ "$done_now" -le 0 ] || estimate=", about $((elapsed * (running + pending) / done_now)) s left"
  else
    line="$line; merging"
    estimate=""
  fi
  if [ "$line" != "$last" ] || [ $((elapsed % 60)) -lt "$interval" ]; then
    echo "slurm: $elapsed s: $line${estimate:-}"
    last="$line"
  fi
  sleep "$interval"
done
