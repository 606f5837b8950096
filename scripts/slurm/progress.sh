#!/usr/bin/env bash
# Progress of a study while it runs: every few seconds one line with the time
# since submission, shards finished (their reports written) of all, how
# many are running or waiting in squeue and how many ended without a report.
# Ends when process WAITER (the sbatch --wait of the merge) ends.
#   scripts/slurm/progress.sh ARRAY_JOB SHARDS DIR WAITER
set -euo pipefail
array_job="$1" shards="$2" dir="$3" waiter="$4"
interval="${RB_PROGRESS_SECONDS:-5}"
start=$SECONDS
last=""
while kill -0 "$waiter" 2>/dev/null; do
  done_count=$(find "$dir/shards" -maxdepth 1 -name 'shard-*.json' | wc -l)
  states=$(squeue -h -r -j "$array_job" -o %t 2>/dev/null || true)
  running=$(grep -c '^R$' <<<"$states" || true)
  pending=$(grep -c '^PD$' <<<"$states" || true)
  failed=$((shards - done_count - running - pending))
  line="shards done $done_count/$shards, running $running, pending $pending"
  [ "$failed" -le 0 ] || line="$line, ended without a report $failed"
  [ "$running" -gt 0 ] || [ "$pending" -gt 0 ] || line="$line; merging"
  if [ "$line" != "$last" ] || [ $(((SECONDS - start) % 60)) -lt "$interval" ]; then
    echo "slurm: $((SECONDS - start)) s: $line"
    last="$line"
  fi
  sleep "$interval"
done
