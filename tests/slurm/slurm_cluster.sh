# tests/slurm/slurm_cluster.sh: sourced by the Slurm tests. start_cluster starts a real, private,
# one-node Slurm cluster (munged, slurmctld and slurmd with a slurm.conf in a temporary folder, all
# stopped and removed on exit) and leaves SLURM_CONF set for sbatch, squeue, scancel and scontrol.
# Needs root (slurmd runs jobs as their user) and the Debian packages slurm-wlm and munge
# (scripts/install-deps.sh --for-tests). When a daemon cannot start, it says why and fails.

fail() {
  echo "slurm test FAILED: $*" >&2
  exit 1
}

# The last lines of the daemons' logs and outputs and of the jobs' (DIR/slurm/*.out in $tmp/work).
show_logs() {
  local log
  for log in "$tmp"/*.log "$tmp"/*.out "$tmp"/work/*/slurm/*.out; do
    [[ -s $log ]] && { echo "--- $log (last lines)" >&2; tail -n 15 "$log" >&2; }
  done
}

cleanup() {
  local pid
  for pid in "${pids[@]}"; do
    kill "$pid" 2>/dev/null
  done
  for pid in "${pids[@]}"; do
    wait "$pid" 2>/dev/null
  done
  rm -rf "$tmp"
}

# start_cluster: $tmp (the temporary folder, with $tmp/work for the test), the daemons running and
# the node idle; or a failure saying which daemon did not come up.
start_cluster() {
  [[ $(id -u) -eq 0 ]] || fail "must run as root (slurmd runs each job as its user; id -u is $(id -u))"
  local tool
  for tool in munged slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
    command -v "$tool" >/dev/null || fail "$tool is not installed (apt-get install slurm-wlm munge, or scripts/install-deps.sh --for-tests)"
  done

  tmp=$(mktemp -d /tmp/frontier-slurm.XXXXXX)
  pids=()
  trap cleanup EXIT

  # Ports of this cluster: free ones, picked per process so that two runs never share them.
  local base=$((20000 + ($$ % 20000)))
  mkdir -p "$tmp/state" "$tmp/spool" "$tmp/run" "$tmp/work"
  chmod 711 "$tmp" # munged wants its socket folder searchable by all

  # munge: a private key and socket.
  dd if=/dev/urandom of="$tmp/munge.key" bs=1024 count=1 status=none
  chmod 400 "$tmp/munge.key"
  munged --foreground --force --key-file="$tmp/munge.key" --socket="$tmp/munge.socket" \
    --pid-file="$tmp/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munged.seed" \
    >"$tmp/munged.out" 2>&1 &
  pids+=($!)

  local hardware node_line
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

  local i
  for i in $(seq 50); do [[ -S $tmp/munge.socket ]] && break; sleep 0.1; done
  [[ -S $tmp/munge.socket ]] || { show_logs; fail "munged did not start (no socket $tmp/munge.socket)"; }

  slurmctld -D -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
  pids+=($!)
  slurmd -D -f "$SLURM_CONF" -N localhost >"$tmp/slurmd.out" 2>&1 &
  pids+=($!)

  # The node must come up idle.
  local up=0 state pid
  for i in $(seq 150); do
    state=$(sinfo -h -n localhost -o %T 2>/dev/null | head -n 1)
    if [[ $state == idle* ]]; then up=1; break; fi
    for pid in "${pids[@]}"; do
      kill -0 "$pid" 2>/dev/null || { cat "$tmp/slurmctld.out" "$tmp/slurmd.out" >&2; show_logs; fail "a daemon (pid $pid) exited while starting"; }
    done
    sleep 0.2
  done
  [[ $up -eq 1 ]] || { sinfo >&2; show_logs; fail "the node did not become idle in 30 s (state '${state:-none}')"; }
}

# wait_for_queue SECONDS [JOBID...]: until the given jobs (or, without any, all jobs) have left the
# queue, completing ones included; fails after SECONDS.
wait_for_queue() {
  local seconds=$1 i
  shift
  local jobs=()
  [[ $# -gt 0 ]] && jobs=(-j "$(IFS=,; echo "$*")")
  for i in $(seq $((seconds * 5))); do
    [[ -z $(squeue -h -o %i "${jobs[@]}" 2>/dev/null) ]] && return 0
    sleep 0.2
  done
  squeue >&2
  show_logs
  fail "the jobs ${*:-of the queue} did not finish in $seconds s"
}

# strip_wall CSV: the batch.csv without its wall-clock columns (the last ones, named wall_*).
strip_wall() {
  awk -F, 'BEGIN { OFS = "," }
    /^#/ { print; next }
    !n { for (i = 1; i <= NF; i++) if ($i ~ /^wall_/) { n = i - 1; break } }
    { NF = n; print }' "$1"
}

# same_as_single_machine FRONTIER PLAN DIR JOBS: DIR/batch.csv has JOBS rows, all done, and equals
# a run of PLAN on this machine alone byte for byte, apart from the wall-clock columns.
same_as_single_machine() {
  local frontier=$1 plan=$2 dir=$3 jobs=$4 rows
  [[ -f $dir/batch.csv ]] || { show_logs; fail "the merge job wrote no $dir/batch.csv"; }
  rows=$(grep -vc '^#' "$dir/batch.csv")
  [[ $rows -eq $((jobs + 1)) ]] || fail "$dir/batch.csv has $((rows - 1)) jobs, expected $jobs"
  [[ $(grep -c ',done,' "$dir/batch.csv") -eq $jobs ]] || fail "not every job is done in $dir/batch.csv"
  "$frontier" batch "$plan" --out "$dir.local" --jobs 2 --quiet || fail "the single-machine batch failed"
  "$frontier" batch "$plan" --out "$dir.local" --merge >/dev/null || fail "the single-machine merge failed"
  if ! diff <(strip_wall "$dir.local/batch.csv") <(strip_wall "$dir/batch.csv") >&2; then
    fail "$dir/batch.csv of the Slurm run differs from the single-machine run's"
  fi
}
