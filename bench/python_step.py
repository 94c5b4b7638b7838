#!/usr/bin/env python3
"""The Python half of bench/python_step.sh: the loop bench/step_loop.cpp times, written with the
frontier module. One measurement per process:

    python_step.py SCENE STEPS step [REPS]    STEPS calls of sim.step()
    python_step.py SCENE STEPS read [REPS]    the same, reading sim.positions after each step
    python_step.py SCENE STEPS peek [REPS]    one step, then STEPS reads of sim.positions alone
    python_step.py SCENE STEPS batch [REPS]   one call of sim.step(STEPS)

As step_loop: the scene is loaded afresh for each of REPS repetitions (default 3), the fastest loop
kept, times are the process's CPU time (time.process_time), and one line is printed:
`mode=M bodies=N steps=S seconds=T per_step_us=U` (the loop only; loading is not timed). Needs the
module on PYTHONPATH (BUILD/python).
"""
import sys
import time

import frontier

clock = time.process_time


def loop(scene, steps, mode):
    """CPU seconds of one loop of `mode` over `steps` steps of a fresh load of `scene`, a checksum
    of what was read, the number of bodies."""
    sim = frontier.load(scene)
    checksum = 0.0
    step = sim.step
    if mode == "step":
        start = clock()
        for _ in range(steps):
            step()
        elapsed = clock() - start
    elif mode == "read":
        start = clock()
        for _ in range(steps):
            step()
            checksum += sim.positions[0, 2]
        elapsed = clock() - start
    elif mode == "peek":
        step()
        start = clock()
        for _ in range(steps):
            checksum += sim.positions[0, 2]
        elapsed = clock() - start
    else:
        start = clock()
        step(steps)
        elapsed = clock() - start
    assert sim.steps_taken == (1 if mode == "peek" else steps)
    return elapsed, checksum, len(sim.body_names)


def main():
    if len(sys.argv) not in (4, 5) or sys.argv[3] not in ("step", "read", "peek", "batch"):
        sys.exit("usage: python_step.py SCENE STEPS step|read|peek|batch [REPS]")
    scene, steps, mode = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    reps = int(sys.argv[4]) if len(sys.argv) == 5 else 3
    runs = [loop(scene, steps, mode) for _ in range(reps)]
    best = min(r[0] for r in runs)
    print("mode=%s bodies=%d steps=%d seconds=%.6f per_step_us=%.4f checksum=%.3g"
          % (mode, runs[0][2], steps, best, 1e6 * best / steps, sum(r[1] for r in runs)))


if __name__ == "__main__":
    main()
