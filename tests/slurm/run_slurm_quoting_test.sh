#!/usr/bin/env bash
# tests/slurm/run_slurm_quoting_test.sh FRONTIER SOURCE_DIR: `frontier batch --slurm --submit` on a
# real, private, one-node Slurm cluster (tests/slurm/slurm_cluster.sh) with hostile values: an
# output folder named with a space, quotes, $(...), backticks, '%' and '#', --partition, --time,
# and a URDF whose meshes are found only through a relative --package-path. Both array tasks and
# the merge run: each task's log is where the folder says (its '%' kept, %a expanded), batch.csv
# has both jobs done, and nothing the names hold ran.
set -uo pipefail
frontier=$(readlink -f "$1")
source_dir=$(readlink -f "$2")
source "$(dirname "$0")/slurm_cluster.sh"
start_cluster

cd "$tmp/work" || fail "no work folder"
cp "$source_dir/scenes/robots/arm6_description/urdf/arm6.urdf" arm6.urdf # away from its package
cp -r "$source_dir/scenes/robots" packages
cat >plan.yaml <<PLAN
scenes: [arm6.urdf]
duration: 0.05
outputs: [stats]
vary:
  dt: [0.001, 0.002]
PLAN
out="runs 'q' \"d\" \$(touch injected-out) \`touch injected-tick\` 100% #h"
"$frontier" batch plan.yaml --out "$out" --slurm --shards 2 --partition test --time 10:00 \
  --package-path packages --submit || { show_logs; fail "frontier batch --slurm --submit failed"; }

wait_for_queue 60 # the array and the merge
for shard in 0 1; do
  [[ -f "$out/slurm/shard-$shard.out" ]] || { ls -R >&2; show_logs; fail "task $shard left no log $out/slurm/shard-$shard.out"; }
done
[[ -f "$out/batch.csv" ]] || { show_logs; fail "the merge wrote no batch.csv in $out"; }
[[ $(grep -c ',done,' "$out/batch.csv") -eq 2 ]] || { cat "$out/batch.csv" >&2; show_logs; fail "not both jobs are done"; }
found=$( (find "$tmp" -name 'injected*'; find / /tmp /root -maxdepth 1 -name 'injected*') 2>/dev/null)
[[ -z $found ]] || fail "a name's shell syntax ran: $found"
echo "slurm quoting test passed: a hostile output folder, --partition, --time and a relative --package-path through sbatch, two tasks and the merge"
