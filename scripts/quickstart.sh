#!/usr/bin/env bash
# Installs what is missing, builds Frontier (Release), and runs the doll: trajectory, stats and
# PNG frames land in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2 --target frontier
mkdir -p out
build/app/frontier run scenes/doll_zero_g.yaml --duration 3 \
  --trajectory out/doll.csv --stats out/doll.json --frames out/frames
echo "wrote out/doll.csv, out/doll.json and out/frames/"
