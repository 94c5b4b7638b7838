#!/usr/bin/env bash
# Records the reference trajectory of every bundled scene (scenes/*.yaml, scenes/*.urdf and
# scenes/robots/*.yaml) into tests/references/<scene>.csv, which
# CTest checks with `frontier check` (one test per scene). Run it after an intended change of
# results, review the diff of the summaries it prints, and commit the new references.
# Usage: scripts/make-references.sh [BUILD_DIR]   (default: build; the frontier binary must exist)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
frontier="$build/app/frontier"
[[ -x "$frontier" ]] || { echo "make-references: no $frontier; build first (cmake --build $build)" >&2; exit 2; }
mkdir -p tests/references
for scene in scenes/*.yaml scenes/*.urdf; do
  name=$(basename "${scene%.*}")
  # 1 s of simulated time, a row every 10 steps: long enough to cover the first impacts, short
  # enough that checking every scene (also in the sanitizer build) takes seconds.
  "$frontier" run "$scene" --duration 1 --record-every 10 --trajectory "tests/references/$name.csv" --quiet
  echo "recorded tests/references/$name.csv"
done
for scene in scenes/robots/*.yaml; do
  name=$(basename "${scene%.*}")
  # The robot scenes over their whole duration (what they show, a push at 2 s, comes later than
  # 1 s; each runs in under a second), a row every 50 steps.
  "$frontier" run "$scene" --record-every 50 --trajectory "tests/references/$name.csv" --quiet
  echo "recorded tests/references/$name.csv"
done
