#!/usr/bin/env bash
# tests/slurm/run_slurm_resume_test.sh FRONTIER SOURCE_DIR: a shard cancelled halfway on a real,
# private, one-node Slurm cluster (tests/slurm/slurm_cluster.sh), resumed as docs/batch.md says.
# `frontier batch --slurm --shards 3 --submit` runs 12 jobs of about half a second; once array task
# 1 has finished a job, `scancel JOBID_1`. Then: the task is CANCELLED, it stopped on the SIGTERM,
# some of its jobs are complete and the others are not (no completed stats, no file under a final
# name, their locks free); the merge job waits forever (DependencyNeverSatisfied) and is cancelled.
# The same command again completes every job without redoing the finished ones (same inode and
# mtime, each task's log counts them as complete before), leaves no partial file, and the merged
# batch.csv equals a single-machine run's, byte for byte apart from the wall-clock columns.
set -uo pipefail
frontier=$(readlink -f "$1")
source_dir=$(readlink -f "$2")
source "$(dirname "$0")/slurm_cluster.sh"
start_cluster

# 12 time steps of the 30-link chain, 10 s simulated each (about 0.5 s of wall time).
cat >"$tmp/work/plan.yaml" <<PLAN
scenes: [$source_dir/scenes/chain30.yaml]
duration: 10
record_every: 50
outputs: [stats, trajectory]
vary:
  dt: [0.001, 0.0011, 0.0012, 0.0013, 0.0014, 0.0015, 0.0016, 0.0017, 0.0018, 0.0019, 0.002, 0.0021]
PLAN
cd "$tmp/work" || fail "no work folder"
mapfile -t all < <("$frontier" batch plan.yaml --out cluster --list | cut -d' ' -f1)
mapfile -t victims < <("$frontier" batch plan.yaml --out cluster --list --shard 1/3 | cut -d' ' -f1)
[[ ${#all[@]} -eq 12 && ${#victims[@]} -eq 4 ]] || fail "the plan has ${#all[@]} jobs, shard 1 of 3 ${#victims[@]}; expected 12 and 4"

# Complete as docs/batch.md defines it: stats saying "completed": true and the trajectory in place.
complete() {
  grep -q '"completed": true' "cluster/jobs/$1/stats.json" 2>/dev/null && [[ -f cluster/jobs/$1/trajectory.csv ]]
}
count_complete() {
  local n=0 id
  for id in "$@"; do complete "$id" && n=$((n + 1)); done
  echo "$n"
}
# "ID INODE MTIME" of the stats and trajectory of every complete job.
stamps() {
  local id file
  for id in "${all[@]}"; do
    complete "$id" || continue
    for file in stats.json trajectory.csv; do
      echo "$id/$file $(stat -c '%i %.9Y' "cluster/jobs/$id/$file")"
    done
  done
}
submit() {
  local said
  said=$("$frontier" batch plan.yaml --out cluster --slurm --shards 3 --submit) || { show_logs; fail "frontier batch --slurm --submit failed"; }
  echo "$said" >&2
  array=$(sed -n 's/^Submitted the array job \([0-9]*\) and the merge job \([0-9]*\)\.$/\1/p' <<<"$said")
  merge=$(sed -n 's/^Submitted the array job \([0-9]*\) and the merge job \([0-9]*\)\.$/\2/p' <<<"$said")
  [[ -n $array && -n $merge ]] || fail "no job ids in the output of --submit"
}

submit
started=$SECONDS
task="${array}_1"
# Cancel task 1 once it has finished a job (its 4 jobs run one after another).
for i in $(seq 1200); do
  [[ $(count_complete "${victims[@]}") -ge 1 ]] && break
  sleep 0.05
done
[[ $(count_complete "${victims[@]}") -ge 1 ]] || { show_logs; fail "task $task finished no job in 60 s"; }
scancel "$task" || fail "scancel $task failed"
wait_for_queue 30 "$task"
echo "task $task left the queue $((SECONDS - started)) s after the submission" >&2

state=$(scontrol -o show job "$task" | grep -o 'JobState=[A-Z_]*')
[[ $state == JobState=CANCELLED ]] || fail "task $task ended as '$state', expected JobState=CANCELLED"
log=cluster/slurm/shard-1.out
grep -q 'SIGTERM: the batch stopped' "$log" || { cat "$log" >&2; fail "task $task did not stop on its SIGTERM (no 'SIGTERM: the batch stopped' in $log)"; }
finished=$(count_complete "${victims[@]}")
[[ $finished -lt 4 ]] || fail "task $task completed its 4 jobs before scancel; make the jobs longer"
for id in "${victims[@]}"; do
  complete "$id" && continue
  folder=cluster/jobs/$id
  ! grep -q '"completed": true' "$folder/stats.json" 2>/dev/null || fail "$id was interrupted but its stats say completed"
  [[ ! -e $folder/trajectory.csv ]] || fail "$id was interrupted but has $folder/trajectory.csv"
  [[ -z $(find "$folder" -name '*.tmp-*' 2>/dev/null) ]] || fail "$id left temporary files: $(find "$folder" -name '*.tmp-*')"
  if [[ -e $folder/.lock ]]; then
    flock -n "$folder/.lock" true || fail "$id: its lock $folder/.lock is still held after the cancel"
  fi
done
# The job that was running (the log says which): its stats say not completed, its rows are kept
# under the .failed name.
interrupted=$(grep -o '[0-9]\{4\}-[^:]*: interrupted' "$log" | cut -d: -f1)
for id in $interrupted; do
  grep -q '"completed": false' "cluster/jobs/$id/stats.json" || fail "the interrupted job $id has no stats saying \"completed\": false"
  [[ -f cluster/jobs/$id/trajectory.failed.csv ]] || fail "the interrupted job $id kept no trajectory.failed.csv"
done
echo "task $task cancelled with $finished of its 4 jobs complete; interrupted while running: ${interrupted:-none (the signal came between two jobs)}" >&2

# The rest of the array ends; the merge job waits for a dependency that can never be met.
wait_for_queue 60 "$array"
reason=
for i in $(seq 100); do
  reason=$(squeue -h -j "$merge" -o %r 2>/dev/null)
  [[ $reason == DependencyNeverSatisfied ]] && break
  sleep 0.2
done
[[ $reason == DependencyNeverSatisfied ]] || { squeue >&2; fail "the merge job $merge waits with reason '$reason', expected DependencyNeverSatisfied"; }
scancel "$merge" || fail "scancel $merge failed"
wait_for_queue 30 "$merge"
[[ $(count_complete "${all[@]}") -eq $((8 + finished)) ]] || fail "$(count_complete "${all[@]}") jobs complete after the cancel, expected $((8 + finished))"
stamps >before.txt
[[ $(wc -l <before.txt) -eq $((2 * (8 + finished))) ]] || fail "before.txt has $(wc -l <before.txt) stamps, expected $((2 * (8 + finished)))"

# Resume: the same command again.
submit
wait_for_queue 60
for shard in 0 1 2; do
  before=4
  [[ $shard -eq 1 ]] && before=$finished
  expected="batch: 4 jobs (shard $shard of 3): $((4 - before)) run, $before complete before, 0 running elsewhere, 0 failed, 0 not run"
  grep -qF "$expected" "cluster/slurm/shard-$shard.out" || { cat "cluster/slurm/shard-$shard.out" >&2; fail "the rerun of shard $shard did not say '$expected'"; }
done
[[ $(count_complete "${all[@]}") -eq 12 ]] || fail "after the rerun $(count_complete "${all[@]}") of 12 jobs are complete"
stamps >after.txt
if ! diff before.txt <(grep -Ff <(cut -d' ' -f1 before.txt) after.txt) >&2; then
  fail "the rerun rewrote files of jobs complete before it (inode and mtime above)"
fi
for id in "${all[@]}"; do
  files=$(cd "cluster/jobs/$id" && LC_ALL=C ls -A | tr '\n' ' ')
  [[ $files == ".lock stats.json trajectory.csv " ]] || fail "cluster/jobs/$id holds '$files', expected .lock stats.json trajectory.csv"
done
same_as_single_machine "$frontier" plan.yaml cluster 12
echo "slurm resume test passed: task 1 cancelled with $finished of 4 jobs complete, the rerun ran the other $((4 - finished)) and no finished job again, batch.csv equal to the single machine's ($((SECONDS - started)) s)"
