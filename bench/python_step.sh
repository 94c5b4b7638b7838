#!/usr/bin/env bash
# bench/python_step.sh: what the Python module adds to a step loop (docs/benchmarks.md, "Python").
# The same loop in C++ (bench/step_loop.cpp: run::Simulation::step(), optionally copying the
# positions each step) and in Python (bench/python_step.py: sim.step(), optionally reading
# sim.positions each step), run alternately, a fresh process each, ROUNDS times, on
#   doll      scenes/falling_doll.yaml, 3000 steps (the whole fall)
#   chain100  a chain of 100 boxes on ball joints (scenes/tools/make_chain.py 100), 1000 steps
#   ball      one free ball in empty space, 20000 steps: the step itself costs little, so the
#             difference per call is the fixed overhead of a Python step() call
# Each process keeps the fastest of 3 loops, timed in CPU time (see step_loop.cpp). Prints per
# scene and mode the median and range over the rounds of the time per step (us) and the ratio
# Python / C++ of the medians and of the minima (on a busy machine the fastest rounds are the
# least disturbed ones); then the fixed overhead of a Python step() call (ball, Python minus
# C++) and the cost of reading the positions once (both languages, `peek`: reads without steps).
#
#   bench/python_step.sh [BUILD] [ROUNDS]    (BUILD: default build; ROUNDS: default 5, at least 5)
# BUILD must hold bench/step_loop (-DFRONTIER_BENCHMARKS=ON) and python/frontier; the environment
# variable PYTHON_BUILD names another build folder for the module (compare like with like: the
# same sources and flags).
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(dirname "$here")
build=$(cd "${1:-$repo/build}" && pwd)
rounds=${2:-5}
pybuild=$(cd "${PYTHON_BUILD:-$build}" && pwd)
python=/usr/bin/python3 # Debian's, which has NumPy
if ((rounds < 5)); then
    echo "python_step.sh: at least 5 rounds, got $rounds" >&2
    exit 2
fi
cpp="$build/bench/step_loop"
for need in "$cpp" "$pybuild/python/frontier"; do
    if [[ ! -e $need ]]; then
        echo "python_step.sh: $need is not built" >&2
        exit 2
    fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$python" "$repo/scenes/tools/make_chain.py" 100 "$work/chain100.yaml"
cat >"$work/ball.yaml" <<'EOF'
name: one free ball
simulation: {dt: 0.001, duration: 20.0, gravity: [0, 0, 0], solver: linear}
bodies:
  - {name: ball, shape: {type: sphere, radius: 0.1}, mass: 1.0, position: [0, 0, 1], velocity: [0.1, 0, 0]}
EOF

cases=("doll $repo/scenes/falling_doll.yaml 3000" "chain100 $work/chain100.yaml 1000" "ball $work/ball.yaml 20000")
peeks=100000 # reads of the positions in `peek` mode
results="$work/results.txt"
py() { PYTHONPATH="$pybuild/python" "$python" "$here/python_step.py" "$@"; }
for ((round = 1; round <= rounds; ++round)); do
    for case in "${cases[@]}"; do
        read -r name scene steps <<<"$case"
        for mode in step read; do
            echo "$name cpp $("$cpp" "$scene" "$steps" "$mode")" >>"$results"
            echo "$name python $(py "$scene" "$steps" "$mode")" >>"$results"
        done
        echo "$name python $(py "$scene" "$steps" batch)" >>"$results"
        echo "$name cpp $("$cpp" "$scene" "$peeks" peek)" >>"$results"
        echo "$name python $(py "$scene" "$peeks" peek)" >>"$results"
    done
    echo "round $round of $rounds done" >&2
done

"$python" - "$results" "$rounds" <<'EOF'
import collections
import statistics
import sys

rows = collections.defaultdict(list)  # (scene, engine, mode) -> per-step us, one per round
bodies = {}
for line in open(sys.argv[1]):
    fields = line.split()
    values = dict(field.split("=", 1) for field in fields[2:])
    rows[(fields[0], fields[1], values["mode"])].append(float(values["per_step_us"]))
    bodies[fields[0]] = values["bodies"]


def describe(values):
    return "%9.3f [%9.3f, %9.3f]" % (statistics.median(values), min(values), max(values))


print("CPU time per step, us: median [min, max] over %s rounds (a process each, fastest of 3 loops)"
      % sys.argv[2])
print("%-9s %6s %-7s %-31s %-31s %s" % ("scene", "bodies", "loop", "C++", "Python",
                                         "Python/C++ (medians, minima)"))


def ratios(p, c):
    return "%.3f  %.3f" % (statistics.median(p) / statistics.median(c), min(p) / min(c))


for scene in ("doll", "chain100", "ball"):
    for mode in ("step", "read"):
        c, p = rows[(scene, "cpp", mode)], rows[(scene, "python", mode)]
        print("%-9s %6s %-7s %-31s %-31s %s" % (scene, bodies[scene], mode, describe(c), describe(p), ratios(p, c)))
    b = rows[(scene, "python", "batch")]
    print("%-9s %6s %-7s %-31s %-31s %s" % (scene, bodies[scene], "step(n)", "", describe(b),
                                            ratios(b, rows[(scene, "cpp", "step")])))
print("(step: step() alone; read: step() then the positions; step(n): one Python call for all steps)")
print()
overhead = [p - c for p, c in zip(rows[("ball", "python", "step")], rows[("ball", "cpp", "step")])]
print("fixed overhead of a Python sim.step() call (ball, Python - C++ per step, paired by round): %s us"
      % describe(overhead).strip())
for scene in ("doll", "chain100", "ball"):
    print("reading the positions once, %-8s (%3s bodies): Python %s us, C++ %s us"
          % (scene, bodies[scene], describe(rows[(scene, "python", "peek")]).strip(),
             describe(rows[(scene, "cpp", "peek")]).strip()))
EOF
