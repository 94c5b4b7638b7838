#!/bin/sh
# frontier_peers with two time steps and --chart: sweep.dat holds one block per engine with a point
# (`cost error "dt label"`) per time step, sweep.gp its script; --chart with several time steps and
# no common reference (--reference-dt) is refused with exit code 2.
# Usage: chart_test.sh FRONTIER_PEERS FOLDER
set -u
peers=$1
out=$2
rm -rf "$out"
"$peers" --chain 5 --duration 0.02 --dt 0.002,0.001 --reference-dt 0.00025 \
  --engines frontier-rattle,bullet-multibody --chart "$out" >/dev/null || { echo "the run failed"; exit 1; }
for engine in frontier-rattle bullet-multibody; do
  points=$(sed -n "/^# $engine\$/,/^\$/p" "$out/sweep.dat" | grep -c '^[0-9]')
  [ "$points" -eq 2 ] || { echo "$engine: $points points in sweep.dat, expected 2"; exit 1; }
done
[ -s "$out/sweep.gp" ] || { echo "no sweep.gp"; exit 1; }
"$peers" --chain 5 --duration 0.02 --dt 0.002,0.001 --chart "$out" 2>/dev/null
status=$?
[ "$status" -eq 2 ] || { echo "--chart without --reference-dt: exit $status, expected 2"; exit 1; }
echo "ok"
