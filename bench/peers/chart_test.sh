#!/bin/sh
# frontier_peers with two time steps and --chart: sweep.dat holds one block per engine with a point
# (`cost error "dt label"`) per time step, sweep.gp its script; --chart with several time steps and
# no common reference (--reference-dt) is refused with exit code 2; --chart-accuracy joint-gap
# needs no reference and puts each engine's largest joint gap (the CSV's max_joint_gap_m) on the
# y axis.
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
rm -rf "$out"
"$peers" --chain 5 --duration 0.02 --dt 0.002,0.001 --engines frontier-rattle,bullet-si \
  --chart "$out" --chart-accuracy joint-gap --csv "$out.csv" >/dev/null || { echo "the joint-gap run failed"; exit 1; }
grep -q "set ylabel 'joint gap (m)" "$out/sweep.gp" || { echo "sweep.gp: no joint-gap axis"; exit 1; }
# Each point's y is the engine's joint gap at that dt, as the CSV gives it (to its 3 digits).
for engine in frontier-rattle bullet-si; do
  for dt in 0.002 0.001; do
    csv=$(awk -F, -v e="$engine" -v d="$dt" '$3 == e && $4 == d { print $8 }' "$out.csv")
    label=$(awk -v d="$dt" 'BEGIN { printf "%g ms", d * 1000 }')
    dat=$(sed -n "/^# $engine\$/,/^\$/p" "$out/sweep.dat" | grep "\"$label\"" | awk '{ printf "%.3g", $2 }')
    [ -n "$csv" ] && [ "$csv" = "$dat" ] || { echo "$engine at $dt: sweep.dat $dat, CSV $csv"; exit 1; }
  done
done
"$peers" --chain 5 --duration 0.02 --chart "$out" --chart-accuracy gap 2>/dev/null
status=$?
[ "$status" -ne 0 ] || { echo "--chart-accuracy gap was accepted"; exit 1; }
echo "ok"
