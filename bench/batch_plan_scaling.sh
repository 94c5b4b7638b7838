#!/usr/bin/env bash
# bench/batch_plan_scaling.sh: how the time to read, expand and list a batch plan grows with its
# size (docs/benchmarks.md, "Batch plans"). Times `frontier batch PLAN --list` (reads the plan,
# checks it, expands the jobs and names their folders; runs nothing) for
#   * `vary: {seed: [0, 1, ..., N-1]}` on one scene, N = 10 000, 100 000, 1 000 000;
#   * `scenes: ['s/*.yaml']`, a glob matching N tiny scene files, N = 1 000, 10 000, 100 000;
# and prints the wall and CPU seconds, the peak memory and CPU seconds / (N log2 N) in microseconds:
# a constant last column is O(N log N) growth.
#
#   bench/batch_plan_scaling.sh [path/to/frontier]    (default: build/app/frontier)
set -euo pipefail

frontier=${1:-build/app/frontier}
frontier=$(cd "$(dirname "$frontier")" && pwd)/$(basename "$frontier")
[[ -x $frontier ]] || { echo "no frontier executable at $frontier" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/batch_plan_scaling.XXXXXX")
trap 'rm -rf "$work"' EXIT

cat >"$work/ball.yaml" <<'EOF'
bodies:
  - {name: ball, shape: {type: sphere, radius: 0.1}, mass: 1, position: [0, 0, 1]}
EOF

# time_list KIND N PLAN: one line of the table. CPU seconds (user + system) as well as wall seconds:
# on a shared machine the wall time also counts other tenants' turns.
time_list() {
    local kind=$1 n=$2 plan=$3 jobs wall cpu rss
    /usr/bin/time -f '%e %U %S %M' -o "$work/time" "$frontier" batch "$plan" --out "$work/out" --list >"$work/list"
    jobs=$(wc -l <"$work/list")
    [[ $jobs -eq $n ]] || { echo "$kind $n: listed $jobs jobs" >&2; exit 1; }
    read -r wall user system rss <"$work/time"
    cpu=$(echo "$user + $system" | bc -l)
    printf '| %-5s | %9d | %8.2f | %8.2f | %7d | %15.3f |\n' "$kind" "$n" "$wall" "$cpu" "$((rss / 1024))" \
        "$(echo "$cpu * 1000000 / ($n * l($n) / l(2))" | bc -l)"
}

echo "| plan  |      jobs |   wall s |    CPU s | MiB RSS | CPU us / (N log2 N) |"
echo "|-------|-----------|----------|----------|---------|---------------------|"
for n in 10000 100000 1000000; do
    { echo "scenes: [ball.yaml]"; echo "duration: 0.01"; echo "vary:"; echo "  seed:"; seq 0 $((n - 1)) | sed 's/^/    - /'; } \
        >"$work/seeds.yaml"
    time_list seeds "$n" "$work/seeds.yaml"
done
mkdir "$work/s"
made=0
for n in 1000 10000 100000; do
    (cd "$work/s" && seq -f 'scene%06.0f.yaml' "$made" $((n - 1)) | xargs touch)
    made=$n
    printf "scenes: ['s/*.yaml']\nduration: 0.01\n" >"$work/glob.yaml"
    time_list glob "$n" "$work/glob.yaml"
done
