#!/usr/bin/env bash
# tests/slurm/run_slurm_test.sh FRONTIER SOURCE_DIR: `frontier batch --slurm --submit` on a real,
# private, one-node Slurm cluster (munged, slurmctld and slurmd started here with a slurm.conf in a
# temporary folder, stopped on exit): a plan of 12 jobs as an array of 3 shards plus the merge job;
# its batch.csv must equal a single-machine run's, byte for byte apart from the wall-clock columns.
# Needs root (slurmd runs jobs as their user) and the Debian packages slurm-wlm and munge
# (scripts/install-deps.sh --for-tests). When a daemon cannot start, it says why and fails.
set -uo pipefail
frontier=$(readlink -f "$1")
source_dir=$(readlink -f "$2")

fail() {
  echo "slurm test FAILED: $*" >&2
  exit 1
}

[[ $(id -u) -eq 0 ]] || fail "must run as root (slurmd runs each job as its user; id -u is $(id -u))"
for tool in munged slurmctld slurmd sbatch squeue scontrol sinfo; do
  command -v "$tool" >/dev/null || fail "$tool is not installed (apt-get install slurm-wlm munge, or scripts/install-deps.sh --for-tests)"
done

tmp=$(mktemp -d /tmp/frontier-slurm.XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do
    kill "$pid" 2>/dev/null
  done
  for pid in "${pids[@]}"; do
    wait "$pid" 2>/dev/null
  done
  rm -rf "$tmp"
}
trap cleanup EXIT

show_logs() {
  for log in "$tmp"/munged.log "$tmp"/slurmctld.log "$tmp"/slurmd.log; do
    [[ -f $log ]] && { echo "--- $log (last lines)" >&2; tail -n 15 "$log" >&2; }
  done
  for out in "$tmp"/*.out; do
    [[ -s $out ]] && { echo "--- $out" >&2; tail -n 15 "$out" >&2; }
  done
}

# Ports of this cluster: free ones, picked per process so that two runs never share them.
base=$((20000 + ($$ % 20000)))
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/run"
chmod 711 "$tmp" # munged wants its socket folder searchable by all

# munge: a private key and socket.
dd if=/dev/urandom of="$tmp/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge.key"
munged --foreground --force --key-file="$tmp/munge.key" --socket="$tmp/munge.socket" \
  --pid-file="$tmp/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munged.seed" \
  >"$tmp/munged.out" 2>&1 &
pids+=($!)

hardware=$(slurmd -C | head -n 1) # NodeName=HOST CPUs=... RealMemory=...
node_line="NodeName=localhost ${hardware#NodeName=* } State=UNKNOWN"
cat >"$tmp/slurm.conf" <<CONF
ClusterName=frontiertest
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$base
SlurmdPort=$((base + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge.socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/run/slurmctld.pid
SlurmdPidFile=$tmp/run/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
$node_line
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"

for i in $(seq 50); do [[ -S $tmp/munge.socket ]] && break; sleep 0.1; done
[[ -S $tmp/munge.socket ]] || { show_logs; fail "munged did not start (no socket $tmp/munge.socket)"; }

slurmctld -D -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N localhost >"$tmp/slurmd.out" 2>&1 &
pids+=($!)

# The node must come up idle.
up=0
for i in $(seq 150); do
  state=$(sinfo -h -n localhost -o %T 2>/dev/null | head -n 1)
  if [[ $state == idle* ]]; then up=1; break; fi
  for pid in "${pids[@]}"; do
    kill -0 "$pid" 2>/dev/null || { cat "$tmp/slurmctld.out" "$tmp/slurmd.out" >&2; show_logs; fail "a daemon (pid $pid) exited while starting"; }
  done
  sleep 0.2
done
[[ $up -eq 1 ]] || { sinfo >&2; show_logs; fail "the node did not become idle in 30 s (state '${state:-none}')"; }

# 2 scenes x 3 time steps x 2 solvers = 12 jobs of 0.2 s.
mkdir -p "$tmp/work"
cat >"$tmp/work/plan.yaml" <<PLAN
scenes: [$source_dir/scenes/bouncing_ball.yaml, $source_dir/scenes/pendulum.yaml]
duration: 0.2
outputs: [stats, trajectory]
vary:
  dt: [0.001, 0.002, 0.004]
  solver: [linear, pgs]
PLAN
cd "$tmp/work" || fail "no work folder"
"$frontier" batch plan.yaml --out cluster --slurm --shards 3 --submit || { show_logs; fail "frontier batch --slurm --submit failed"; }
grep -q -- '--array=0-2' cluster/slurm/batch.sbatch || fail "batch.sbatch has no --array=0-2"

# Wait for the array and the merge to leave the queue.
done_ok=0
for i in $(seq 200); do
  if [[ -z $(squeue -h -o %i 2>/dev/null) ]]; then done_ok=1; break; fi
  sleep 0.2
done
[[ $done_ok -eq 1 ]] || { squeue >&2; show_logs; fail "the jobs did not finish in 40 s"; }
[[ -f cluster/batch.csv ]] || { cat cluster/slurm/*.out >&2; show_logs; fail "the merge job wrote no batch.csv"; }
for shard in 0 1 2; do
  [[ -f cluster/slurm/shard-$shard.out ]] || fail "shard $shard left no output (cluster/slurm/shard-$shard.out)"
done

# The same plan on this machine alone.
"$frontier" batch plan.yaml --out local --jobs 2 --quiet || fail "the single-machine batch failed"
"$frontier" batch plan.yaml --out local --merge >/dev/null || fail "the single-machine merge failed"

# Compare without the wall-clock columns (the last ones, named wall_*).
strip() {
  awk -F, 'BEGIN { OFS = "," }
    /^#/ { print; next }
    !n { for (i = 1; i <= NF; i++) if ($i ~ /^wall_/) { n = i - 1; break } }
    { NF = n; print }' "$1"
}
rows=$(grep -vc '^#' cluster/batch.csv)
[[ $rows -eq 13 ]] || fail "cluster/batch.csv has $((rows - 1)) jobs, expected 12"
[[ $(grep -c ',done,' cluster/batch.csv) -eq 12 ]] || fail "not every job is done in cluster/batch.csv"
if ! diff <(strip local/batch.csv) <(strip cluster/batch.csv) >&2; then
  fail "batch.csv of the Slurm run differs from the single-machine run's"
fi
echo "slurm test passed: 12 jobs in 3 array tasks and a merge, batch.csv equal to the single machine's"
