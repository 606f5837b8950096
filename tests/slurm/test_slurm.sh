#!/usr/bin/env bash
# scripts/slurm/ on a real scheduler: a single-node SLURM cluster on
# localhost (munged, slurmctld, slurmd as root, every file in a temporary
# folder, ports of their own), then
#   1. a study in 3 shards (the quick preset, stability included), merged and
#      plotted by the dependent job: its report must equal the unsharded run
#      in every accuracy field;
#   2. a study whose shard 1 sees a broken scene: the other shards' reports
#      stay, the merge names shard 1 as missing, and `submit.sh --only 1`
#      completes it;
#   3. the regime study on a small grid (4 generated scenes) in 3 shards:
#      merged and plotted, equal to the unsharded run (compare.py sees no
#      change but timing), with its regime-<target>.png and findings line.
# Everything started here is stopped by its process id on exit, failure
# included. Exit 77 (skipped) without root or without slurm-wlm and munge
# (scripts/install-deps.sh --tests installs them).
#   tests/slurm/test_slurm.sh [ROLLBENCH]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
rollbench="$(realpath "${1:-$root/build/release/rollbench}")"
limit="${RB_SLURM_TEST_SECONDS:-150}"   # each wait on the scheduler
[ "$(id -u)" -eq 0 ] || { echo "skipped: the test cluster's daemons run as root"; exit 77; }
for tool in munged mungekey slurmctld slurmd sbatch squeue sinfo scancel; do
  command -v "$tool" >/dev/null || { echo "skipped: no $tool (scripts/install-deps.sh --tests installs slurm-wlm, munge)"; exit 77; }
done
[ -x "$rollbench" ] || { echo "FAIL: no rollbench at $rollbench"; exit 1; }

tmp="$(mktemp -d /tmp/rb-slurm-test.XXXXXX)"
pids=()
failed=1
stop_all() {
  # jobs first, so that no job step outlives its slurmd; then the daemons
  if [ -n "${SLURM_CONF:-}" ] && [ ${#pids[@]} -ge 2 ]; then
    scancel --quiet --full -u root 2>/dev/null || true
    for _ in $(seq 20); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 0.5; done
  fi
  local i
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null || true; done
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    for _ in $(seq 20); do kill -0 "${pids[i]}" 2>/dev/null || break; sleep 0.25; done
    kill -9 "${pids[i]}" 2>/dev/null || true
  done
  if [ "$failed" = 1 ]; then
    echo "== the daemons' logs, ends"
    for log in "$tmp"/*.log "$tmp"/study*/logs/*.log; do [ -f "$log" ] && { echo "-- $log"; tail -n 15 "$log"; }; done
  fi
  rm -rf "$tmp"
}
trap stop_all EXIT
fail() { echo "FAIL: $*"; exit 1; }
free_port() { /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
wait_for() {  # wait_for SECONDS WHAT COMMAND...
  local seconds="$1" what="$2"
  shift 2
  for _ in $(seq $((seconds * 4))); do "$@" >/dev/null 2>&1 && return 0; sleep 0.25; done
  fail "$what did not come up within $seconds s"
}

# munge: its own key, socket, pid, log and seed files
mkdir -m 700 "$tmp/munge"
mungekey --create --keyfile="$tmp/munge/munge.key"
socket="$tmp/munge/munge.socket"
munged --foreground --force --key-file="$tmp/munge/munge.key" --socket="$socket" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munge/munged.seed" >"$tmp/munged.out" 2>&1 &
pids+=($!)
wait_for 10 munged bash -c "munge -n -S '$socket' | unmunge -S '$socket'"

# slurm: controller and one node on localhost, the node as slurmd -C sees it
node="$(hostname -s)"
hardware="$(slurmd -C | head -1 | sed 's/^NodeName=[^ ]* //')"
mkdir -p "$tmp/state" "$tmp/spool"
export SLURM_CONF="$tmp/slurm.conf"
cat > "$SLURM_CONF" <<CONF
ClusterName=rbtest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
SwitchType=switch/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
ReturnToService=2
MailProg=/bin/true
NodeName=$node NodeAddr=127.0.0.1 $hardware State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -D -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
wait_for 30 slurmctld scontrol ping
slurmd -D -f "$SLURM_CONF" -N "$node" >"$tmp/slurmd.out" 2>&1 &
pids+=($!)
wait_for 30 "the node" bash -c '[ "$(sinfo -h -N -o %T)" = idle ]'
echo "== cluster up: $(sinfo -h -N -o '%N %T %c CPUs')"

submit() { timeout "$limit" "$root/scripts/slurm/submit.sh" "$@"; }
same_accuracy() { /usr/bin/python3 "$root/tests/slurm/same_accuracy.py" "$@"; }

# 1. three shards against the unsharded run
"$rollbench" run --preset quick --no-finer-steps --out "$tmp/whole.json" >/dev/null 2>&1
ROLLBENCH="$rollbench" submit --dir "$tmp/study" --shards 3 --wait -- --preset quick | tee "$tmp/submit.out" \
  || fail "the sharded study did not complete (exit ${PIPESTATUS[0]})"
grep -Eq '^slurm: [0-9]+ s: shards done [0-3]/3, running [0-3], pending [0-3]' "$tmp/submit.out" \
  || fail "no progress lines while waiting"
[ -f "$tmp/study/plots/summary.md" ] || fail "the merge job made no plots"
same_accuracy "$tmp/whole.json" "$tmp/study/report.json" || fail "the merged report differs from the unsharded run"
echo "== ok: 3 shards merged equal the unsharded run in every accuracy field"

# 2. shard 1 fails: a node whose copy of the scene is broken
small=(--scenes "valley-sideways,$tmp/my-scene.json" --integrators rk4,rkmk4,odeint-dopri5-adaptive
  --h 2^-4..2^-7 --tol 1e-5,1e-7 --repeats 1 --no-stability)
cp "$root/problems/scenes/plane.json" "$tmp/my-scene.json"
sed 's/"radius": *[0-9.eE+-]*/"radius": -1/' "$tmp/my-scene.json" > "$tmp/broken-scene.json"
grep -q '"radius": -1' "$tmp/broken-scene.json" || fail "could not break the scene"
cat > "$tmp/rollbench-node" <<WRAP
#!/usr/bin/env bash
args=("\$@")
[[ " \$* " != *" --shard 1/3 "* ]] || args=("\${args[@]/my-scene.json/broken-scene.json}")
exec "$rollbench" "\${args[@]}"
WRAP
chmod +x "$tmp/rollbench-node"
rc=0
ROLLBENCH="$tmp/rollbench-node" submit --dir "$tmp/study2" --shards 3 --no-plot --wait -- "${small[@]}" || rc=$?
[ "$rc" -ne 0 ] || fail "a study with a failed shard reported success"
for i in 0 2; do [ -f "$tmp/study2/shards/shard-$i.json" ] || fail "shard $i's report is gone"; done
[ ! -e "$tmp/study2/shards/shard-1.json" ] || fail "the failed shard left a report"
[ ! -e "$tmp/study2/report.json" ] || fail "a merged report was written with a shard missing"
grep -qF "rollbench: 'scenes': in $tmp/broken-scene.json: 'ball.radius': the radius must be > 0" \
  "$tmp/study2/logs/shard-1.log" \
  || fail "shard 1's log does not say what was wrong"
grep -qF "rollbench: 'reports': shard 1 of 3 is missing (given: 0, 2)" "$tmp/study2/logs/merge.log" \
  || fail "the merge did not name the missing shard"
echo "== ok: a failed shard leaves the others' reports and the merge names shard 1"
ROLLBENCH="$rollbench" submit --dir "$tmp/study2" --only 1 --no-plot --wait || fail "rerunning shard 1 failed"
"$rollbench" run "${small[@]}" --no-finer-steps --out "$tmp/whole2.json" >/dev/null 2>&1
same_accuracy "$tmp/whole2.json" "$tmp/study2/report.json" || fail "the completed study differs from the unsharded run"
echo "== ok: --only 1 completed the study, equal to the unsharded run"

# 3. the regime study on a small grid: 3 shards merged and plotted equal the unsharded run
regime=(--preset regime --regime "inertia=1,3;spin=5,50;roughness=0.3;t_end=0.5;bowl=0.1;speed=0.5;held_out=none"
  --integrators rk4,rkmk4,rk-dp54-adaptive,rkmk-dp54-adaptive --h 2^-3..2^-7 --tol 1e-4,1e-6,1e-8,1e-10
  --repeats 1)
"$rollbench" run "${regime[@]}" --no-finer-steps --out "$tmp/regime-whole.json" >/dev/null 2>&1 || fail "the unsharded regime run failed"
ROLLBENCH="$rollbench" submit --dir "$tmp/study3" --shards 3 --wait -- "${regime[@]}" \
  || fail "the sharded regime study did not complete"
same_accuracy "$tmp/regime-whole.json" "$tmp/study3/report.json" || fail "the merged regime report differs"
/usr/bin/python3 "$root/analysis/compare.py" "$tmp/regime-whole.json" "$tmp/study3/report.json" > "$tmp/compare.md"
# timing may differ (per run or pooled per integrator: the shards ran at other times), nothing else may
! grep -Eq '^\| [^|]+ \| [^|]+ \| [^|]+ \| (status|error\.|drift\.|order\.)' "$tmp/compare.md" \
  && ! grep -q "^## Runs only in" "$tmp/compare.md" \
  || { cat "$tmp/compare.md"; fail "compare.py sees more than timing change between the merged and unsharded reports"; }
for target in 1e-04 1e-06 1e-09; do
  [ -f "$tmp/study3/plots/regime-$target.png" ] || fail "the merge job drew no regime-$target.png"
done
grep -q '^- Regime map (4 generated scenes' "$tmp/study3/plots/summary.md" || fail "no regime line in the findings"
echo "== ok: the regime study's 3 shards merge into the unsharded report (compare.py: no change but timing)"
failed=0
echo "PASS"
