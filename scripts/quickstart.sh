#!/usr/bin/env bash
# Installs what is missing, builds Frontier (Release), and runs the falling doll (the paper's figure 8):
# trajectory, stats and PNG frames land in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2 --target frontier
mkdir -p out
build/app/frontier run scenes/falling_doll.yaml \
  --trajectory out/falling_doll.csv --stats out/falling_doll.json --frames out/frames
echo "wrote out/falling_doll.csv, out/falling_doll.json and out/frames/"
