#!/usr/bin/env bash
# Runs the stability suite (docs/stability.md): every scene of scenes/stability/ with every default
# method, one run at a time, then the largest time step at which each still holds (--largest-dt),
# and puts the tables into docs/stability.md between the "stability-table" markers. Builds build/
# (Release) first when needed. robot_in_floor.yaml needs Debian's dart-doc
# (scripts/install-deps.sh --for-tests).
#
#   scripts/stability.sh                      # all scenes, default methods (ten minutes or more)
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

table=$(mktemp)
trap 'rm -f "$table"' EXIT
"$build/app/frontier" stability scenes/stability/*.yaml --largest-dt --out "$table" "$@" >/dev/null

python3 - "$table" docs/stability.md <<'EOF'
import sys
table_path, page_path = sys.argv[1], sys.argv[2]
begin, end = "<!-- stability-table:begin -->", "<!-- stability-table:end -->"
table = open(table_path).read().rstrip("\n")
page = open(page_path).read()
if begin not in page or end not in page:
    sys.exit(f"{page_path}: no {begin} ... {end} markers")
head, rest = page.split(begin, 1)
_, tail = rest.split(end, 1)
open(page_path, "w").write(head + begin + "\n" + table + "\n" + end + tail)
print(f"wrote the table into {page_path}")
EOF
