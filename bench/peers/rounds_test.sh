#!/bin/sh
# frontier_peers with rounds, a baseline and jittered variants on the bundled box pileup, briefly:
# every engine loads and runs the scene (all its steps, no refusal), each row reports the rounds and
# variants asked for, its median time lies within its range, the baseline's ratio to itself is 1 in
# every round, and the table names the baseline; a --baseline that is not among the engines run is
# refused with exit code 2.
# Usage: rounds_test.sh FRONTIER_PEERS SCENES_DIR OUT.csv
set -u
peers=$1
scenes=$2
csv=$3
"$peers" --scene "$scenes/pileup44_boxes.yaml" --duration 0.02 --rounds 2 --baseline bullet-si --variants 1 \
  --csv "$csv" >"$csv.md" 2>/dev/null || { echo "the run failed"; exit 1; }
grep -q "| over bullet-si | range |" "$csv.md" || { echo "the table has no ratio columns"; exit 1; }
grep -q "penetration over 1 variant:" "$csv.md" || { echo "the table has no variant column"; exit 1; }
awk -F, '
  NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
  {
    rows++
    e = $col["engine"]
    if ($col["steps"] != 20) { print e ": " $col["steps"] " steps, expected 20 (note: " $col["note"] ")"; bad = 1 }
    if ($col["rounds"] != 2 || $col["variants"] != 1) { print e ": rounds " $col["rounds"] ", variants " $col["variants"]; bad = 1 }
    if ($col["us_per_step_min"] + 0 > $col["us_per_step"] + 0 || $col["us_per_step"] + 0 > $col["us_per_step_max"] + 0) {
      print e ": median " $col["us_per_step"] " outside " $col["us_per_step_min"] "-" $col["us_per_step_max"]; bad = 1
    }
    if ($col["baseline"] != "bullet-si" || $col["ratio_to_baseline"] == "") { print e ": no ratio to bullet-si"; bad = 1 }
    if (e == "bullet-si" && ($col["ratio_to_baseline"] != 1 || $col["ratio_min"] != 1 || $col["ratio_max"] != 1)) {
      print "bullet-si over itself: " $col["ratio_to_baseline"] " (" $col["ratio_min"] "-" $col["ratio_max"] ")"; bad = 1
    }
    if ($col["variant_penetration_median_m"] == "") { print e ": no penetration over the variants"; bad = 1 }
  }
  END { if (rows != 9) { print rows " rows, expected 9"; bad = 1 } exit bad }
' "$csv" || exit 1
"$peers" --chain 3 --duration 0.01 --engines frontier-euler --baseline bullet-si >/dev/null 2>&1
status=$?
[ "$status" -eq 2 ] || { echo "--baseline of an engine not run: exit $status, expected 2"; exit 1; }
echo "ok"
