#!/usr/bin/env bash
# Runs the stability suite (README "Stability suite"): every scene of scenes/stability/ with every
# default method, one run at a time. Writes the table to docs/stability.md and puts it into
# README.md between the "stability-table" markers. Builds build/ (Release) first when needed.
#
#   scripts/stability.sh                      # all scenes, default methods (a few minutes)
#   scripts/stability.sh --methods linear/euler,pgs:20/euler   # extra flags go to `frontier stability`
#
# BUILD_DIR overrides the build folder (default: build).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
jobs=${JOBS:-2}

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" -j"$jobs" --target frontier

mkdir -p docs
"$build/app/frontier" stability scenes/stability/*.yaml --out docs/stability.md "$@" >/dev/null

python3 - docs/stability.md README.md <<'EOF'
import sys
table_path, readme_path = sys.argv[1], sys.argv[2]
begin, end = "<!-- stability-table:begin -->", "<!-- stability-table:end -->"
table = open(table_path).read().rstrip("\n")
readme = open(readme_path).read()
if begin not in readme or end not in readme:
    sys.exit(f"{readme_path}: no {begin} ... {end} markers; the table is in {table_path}")
head, rest = readme.split(begin, 1)
_, tail = rest.split(end, 1)
open(readme_path, "w").write(head + begin + "\n" + table + "\n" + end + tail)
print(f"wrote {table_path} and the table in {readme_path}")
EOF
