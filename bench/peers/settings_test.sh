#!/bin/sh
# frontier_peers with engines' settings (engine.h): a bad spelling in --engines exits with code 2
# and a message that names the engine and the key; a spelling with settings is a row of its own
# (in the CSV and in the chart's data, by that spelling), and --baseline takes one: its ratio to
# itself is 1.
# Usage: settings_test.sh FRONTIER_PEERS FOLDER
set -u
peers=$1
out=$2
rm -rf "$out" "$out.csv"
refused() {
  message=$("$peers" --chain 3 --duration 0.01 --rounds 1 --engines "$1" 2>&1 >/dev/null)
  status=$?
  [ "$status" -eq 2 ] || { echo "--engines $1: exit $status, expected 2"; exit 1; }
  echo "$message" | grep -qF "$2" || { echo "--engines $1: '$message' does not say '$2'"; exit 1; }
}
refused "bullet-si:iters=20" "engine 'bullet-si': unknown key 'iters'"
refused "frontier-euler,frontier-euler:relative=1" "engine 'frontier-euler': bad value '1' for relative"
refused "ode-quick:iterations=many" "engine 'ode-quick': bad value 'many' for iterations"
refused "ode-direct:iterations=5" "engine 'ode-direct': unknown key 'iterations'"
"$peers" --chain 3 --duration 0.01 --rounds 1 --engines bullet-si:iterations=5 --baseline bullet-si \
  >/dev/null 2>&1
status=$?
[ "$status" -eq 2 ] || { echo "--baseline outside --engines: exit $status, expected 2"; exit 1; }
engines="bullet-si:iterations=1,bullet-si:iterations=50,frontier-euler:tolerance=0.5:relative=0.1"
"$peers" --chain 3 --duration 0.02 --dt 0.002,0.001 --rounds 2 --engines "$engines" \
  --baseline bullet-si:iterations=50 --chart "$out" --chart-accuracy joint-gap --csv "$out.csv" \
  >/dev/null 2>&1 || { echo "the run failed"; exit 1; }
for engine in bullet-si:iterations=1 bullet-si:iterations=50 frontier-euler:tolerance=0.5:relative=0.1; do
  rows=$(awk -F, -v e="$engine" '$3 == e' "$out.csv" | wc -l)
  [ "$rows" -eq 2 ] || { echo "$engine: $rows CSV rows, expected 2"; exit 1; }
  points=$(sed -n "/^# $engine\$/,/^\$/p" "$out/sweep.dat" | grep -c '^[0-9]')
  [ "$points" -eq 2 ] || { echo "$engine: $points points in sweep.dat, expected 2"; exit 1; }
done
ratio=$(awk -F, '$3 == "bullet-si:iterations=50" && $4 == "0.001" { print $17 }' "$out.csv")
[ "$ratio" = "1" ] || { echo "the baseline over itself: '$ratio', expected 1"; exit 1; }
echo "ok"
