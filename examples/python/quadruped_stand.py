#!/usr/bin/env python3
"""The bundled quadruped (scenes/robots/quadruped_stand.yaml) standing on position servos whose
targets come from a Python function of time: it crouches slowly and rises again, twice, then
stands. Frames are drawn with sim.render and written as a video with ffmpeg (when ffmpeg is on
PATH), else as PNG files.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/quadruped_stand.py out/

writes out/quadruped_stand.mp4 (or out/frame_00000.png ...) and prints the trunk's height as it goes.
"""
import math
import pathlib
import shutil
import subprocess
import sys

import frontier
import numpy as np

SCENE = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "robots" / "quadruped_stand.yaml"
DURATION = 10.0  # s
FPS = 30
WIDTH, HEIGHT = 640, 480
LEGS = ("FL", "FR", "RL", "RR")


def crouch(t):
    """The thigh angle (rad) at time t (s): bend from straight legs to 0.5 rad over the first second,
    then twice down to 0.8 rad and back up to 0.2 rad (4 s each), then stand at 0.5 rad."""
    if t < 1.0:
        return 0.5 * (0.5 - 0.5 * math.cos(math.pi * t))  # smooth start, at rest at both ends
    if t < 9.0:
        return 0.5 + 0.3 * math.sin(2.0 * math.pi * (t - 1.0) / 4.0)
    return 0.5


def targets(t):
    """Servo targets by joint name: the knee bends twice as far as the thigh, which keeps each foot
    under its hip (the thigh and the calf are about equally long)."""
    thigh = crouch(t)
    out = {}
    for leg in LEGS:
        out[leg + "_thigh_joint"] = thigh
        out[leg + "_calf_joint"] = -2.0 * thigh
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: quadruped_stand.py OUT_FOLDER")
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)

    sim = frontier.load(SCENE)
    # The servos of the scene drive the thighs and knees; `hold: true` holds the hips.
    actuator = {name: sim.actuator_names.index(name) for name in targets(0.0)}
    base = sim.body_names.index("base")  # the trunk (the URDF's base_link welded to its root link)
    camera = dict(position=[0.9, -0.9, 0.55], look_at=[0.0, 0.0, 0.25], fov=45)  # m, m, degrees

    ffmpeg = shutil.which("ffmpeg")
    video = None
    if ffmpeg:
        # Raw RGB frames through a pipe: no files per frame.
        video = subprocess.Popen(
            [ffmpeg, "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
             "%dx%d" % (WIDTH, HEIGHT), "-r", str(FPS), "-i", "-", "-pix_fmt", "yuv420p",
             str(out / "quadruped_stand.mp4")],
            stdin=subprocess.PIPE)

    steps_per_frame = max(1, round(1.0 / (FPS * sim.dt)))
    frame = 0
    lowest = math.inf
    while sim.time < DURATION - 1e-9:
        if sim.steps_taken % steps_per_frame == 0:
            image = sim.render(WIDTH, HEIGHT, camera=camera)
            if video:
                video.stdin.write(image.tobytes())
            else:
                frontier.write_png(out / ("frame_%05d.png" % frame), image)
            frame += 1
        # The targets for this step, from the function of time.
        for name, value in targets(sim.time).items():
            sim.set_actuator_target(actuator[name], value)
        sim.step()
        height = sim.positions[base, 2]
        lowest = min(lowest, height)
        if sim.steps_taken % 500 == 0:
            print("t = %4.1f s  thigh target %.2f rad  trunk height %.3f m" % (sim.time, crouch(sim.time), height))

    if video:
        video.stdin.close()
        if video.wait() != 0:
            sys.exit("ffmpeg failed")
        print("wrote %s (%d frames)" % (out / "quadruped_stand.mp4", frame))
    else:
        print("wrote %d frames into %s (ffmpeg not found)" % (frame, out))
    # It stood throughout: the trunk stayed about where legs bent as asked put it (hip to knee
    # 0.22 m, knee to foot centre 0.2 m, foot radius 0.025 m, the knee bent twice the thigh angle).
    final = sim.positions[base, 2]
    expected = 0.42 * math.cos(crouch(sim.time)) + 0.025
    print("trunk height: lowest %.3f m, at the end %.3f m (legs as commanded: %.3f m)" % (lowest, final, expected))
    if lowest < 0.2 or abs(final - expected) > 0.05 or not np.all(np.isfinite(sim.positions)):
        sys.exit("the quadruped did not stand as commanded")


if __name__ == "__main__":
    main()
