#!/usr/bin/env bash
# Seeds the fuzz corpora (scripts/fuzz.sh) from the bundled scenes, robots, meshes and reference
# trajectories, and a few batch plans: fuzz/seeds.sh DIR writes DIR/yaml_scene, DIR/urdf, DIR/mesh,
# DIR/trajectory, DIR/scene_steps (the scenes again) and DIR/batch_plan.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$1
rm -rf "$out"
mkdir -p "$out"/{yaml_scene,urdf,mesh,trajectory,scene_steps,batch_plan}

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
cp "$out"/yaml_scene/* "$out/scene_steps/"
# Batch plans over the scenes that fuzz/batch_plan_fuzz.cpp puts beside the plan (docs/batch.md).
printf '%s\n' 'scenes: [ball.yaml]' 'duration: 0.01' 'vary: {dt: [0.001, 0.002]}' >"$out/batch_plan/dt.yaml"
printf '%s\n' 'scenes: ["*.yaml"]' 'duration: 0.01' 'outputs: [stats, trajectory]' 'vary:' \
  '  solver: [linear, pgs]' '  seed: [1, 2]' >"$out/batch_plan/glob.yaml"
printf '%s\n' 'scenes: [ball.yaml, stack.yaml]' 'duration: 0.01' 'set:' '  contact.friction: 0.3' \
  'perturb: {position: 0.01, velocity: 0.1}' 'vary:' '  seed: [3]' '  integrator: [euler, rattle]' \
  >"$out/batch_plan/set.yaml"
printf '%s\n' 'scenes: [ball.yaml]' 'duration: 0.01' 'vary:' '  bodies.ball.mass: [0.5, 1.0]' \
  '  bodies.ball.position: [[0, 0, 2], [0, 0, 3]]' >"$out/batch_plan/paths.yaml"
printf '%s\n' 'scenes: [pendulum.yaml]' 'duration: 0.01' 'shards: 2' 'vary:' '  pgs_iterations: [5, 10]' \
  '  simulation.gravity: [[0, 0, -9.81]]' >"$out/batch_plan/pendulum.yaml"
