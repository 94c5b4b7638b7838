#!/usr/bin/env bash
# Seeds the fuzz corpora (scripts/fuzz.sh) from the bundled scenes, robots, meshes and reference
# trajectories: fuzz/seeds.sh DIR writes DIR/yaml_scene, DIR/urdf, DIR/mesh and DIR/trajectory.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$1
rm -rf "$out"
mkdir -p "$out"/{yaml_scene,urdf,mesh,trajectory}

# Scenes up to 32 KB (chain1000 is the same text a thousand times). The fuzz target reads them as
# if they were in scenes/robots: the top-level scenes' models are one folder up.
for f in scenes/*.yaml scenes/robots/*.yaml scenes/stability/*.yaml; do
  [[ $(stat -c %s "$f") -le 32768 ]] || continue
  name=$(echo "${f#scenes/}" | tr / _)
  if [[ $f == scenes/*/* ]]; then
    cp "$f" "$out/yaml_scene/$name"
  else
    sed -E 's|^(\s*-?\s*urdf:\s*)([^/])|\1../\2|' "$f" >"$out/yaml_scene/$name"
  fi
done
for f in $(find scenes tests -name '*.urdf'); do
  cp "$f" "$out/urdf/$(echo "$f" | tr / _)"
done
# Meshes: the first byte picks the extension (fuzz/mesh_fuzz.cpp).
for f in $(find scenes tests -iname '*.stl' -o -iname '*.obj' -o -iname '*.dae' -o -iname '*.ply' -o -iname '*.off'); do
  case "${f,,}" in
    *.stl) b=0 ;; *.obj) b=1 ;; *.dae) b=2 ;; *.ply) b=3 ;; *.off) b=4 ;;
  esac
  { printf '%s' "$b"; cat "$f"; } >"$out/mesh/$(echo "$f" | tr / _)"
done
# Reference trajectories: their first 40 lines (the header and the first rows).
for f in tests/references/*.csv; do
  head -n 40 "$f" >"$out/trajectory/$(basename "$f")"
done
