#!/usr/bin/env bash
# tests/slurm/run_slurm_test.sh FRONTIER SOURCE_DIR: `frontier batch --slurm --submit` on a real,
# private, one-node Slurm cluster (tests/slurm/slurm_cluster.sh): a plan of 12 jobs as an array of
# 3 shards plus the merge job; its batch.csv must equal a single-machine run's, byte for byte apart
# from the wall-clock columns. Task 1 submitted again alone runs shard 1 of 3 (and skips its jobs).
set -uo pipefail
frontier=$(readlink -f "$1")
source_dir=$(readlink -f "$2")
source "$(dirname "$0")/slurm_cluster.sh"
start_cluster

# 2 scenes x 3 time steps x 2 solvers = 12 jobs of 0.2 s.
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

wait_for_queue 40 # the array and the merge
for shard in 0 1 2; do
  [[ -f cluster/slurm/shard-$shard.out ]] || fail "shard $shard left no output (cluster/slurm/shard-$shard.out)"
done
same_as_single_machine "$frontier" plan.yaml cluster 12

# One task submitted alone, as docs/batch.md resubmits a stopped one, runs its own shard: here all
# 4 of its jobs are complete already.
task=$(sbatch --parsable --array=1 cluster/slurm/batch.sbatch) || fail "sbatch --array=1 failed"
wait_for_queue 30 "${task%%;*}"
expected="batch: 4 jobs (shard 1 of 3): 0 run, 4 complete before"
grep -qF "$expected" cluster/slurm/shard-1.out || { cat cluster/slurm/shard-1.out >&2; fail "sbatch --array=1 did not say '$expected'"; }
echo "slurm test passed: 12 jobs in 3 array tasks and a merge, batch.csv equal to the single machine's; task 1 alone ran shard 1 of 3"
