"""sim.record writes the files `frontier run --trajectory --stats` writes, so that `frontier check`
and `frontier render` work on runs made from Python."""
import json

import frontier
import numpy as np
import pytest

from frontier_testing import read_png, read_trajectory


def data_lines(path):
    """The rows of a CSV without its comment line (which names the scene as it was given)."""
    return [line for line in path.read_text().splitlines() if not line.startswith("#")]


def test_a_recorded_run_passes_frontier_check_and_renders(scenes, tmp_path, frontier_cli):
    scene = scenes / "falling_doll.yaml"
    trajectory, stats = tmp_path / "doll.csv", tmp_path / "doll.json"
    sim = frontier.load(scene)
    with sim.record(trajectory=str(trajectory), stats=str(stats), every=1):
        sim.step(600)
    assert trajectory.is_file() and stats.is_file()
    checked = frontier_cli("check", scene, "--reference", trajectory)
    assert checked.returncode == 0, checked.stdout + checked.stderr

    frames = tmp_path / "frames"
    rendered = frontier_cli("render", trajectory, "--frames", frames, "--quiet")
    assert rendered.returncode == 0, rendered.stderr
    pngs = sorted(frames.glob("*.png"))
    assert len(pngs) >= 10  # 0.6 s of frames
    assert all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in pngs)


def test_the_recorded_files_are_those_of_frontier_run(scenes, tmp_path, frontier_cli):
    scene = scenes / "pileup44.yaml"
    ours, theirs = tmp_path / "python.csv", tmp_path / "cli.csv"
    ours_stats, their_stats = tmp_path / "python.json", tmp_path / "cli.json"
    sim = frontier.load(scene)
    with sim.record(trajectory=str(ours), stats=str(ours_stats)):
        sim.step(150)
    done = frontier_cli("run", scene, "--steps", 150, "--trajectory", theirs, "--stats", their_stats)
    assert done.returncode == 0, done.stderr
    assert data_lines(ours) == data_lines(theirs)
    # The comment lines carry the same settings (scene, dt, solver, steps ...).
    header = lambda path: dict(
        pair.split("=", 1) for pair in path.read_text().splitlines()[0].split(":", 1)[1].split())
    assert header(ours) == header(theirs)
    a, b = json.loads(ours_stats.read_text()), json.loads(their_stats.read_text())
    assert set(a) == set(b)
    for key in ("steps", "bodies", "dt"):
        if key in b:
            assert a[key] == b[key], key


def test_record_every_keeps_every_nth_step(scenes, tmp_path):
    sim = frontier.load(scenes / "pendulum.yaml")
    path = tmp_path / "every.csv"
    with sim.record(trajectory=str(path), every=10):
        sim.step(100)
    times = sorted(read_trajectory(path))
    # Each row of `frontier run --record-every 10`: the start and every tenth step after it.
    assert times[-1] == sim.time
    steps = [round(t / sim.dt) for t in times]
    assert all(s % 10 == 0 for s in steps)
    assert steps[-1] == 100 and len(steps) in (10, 11)


def test_a_recording_interrupted_by_an_exception_is_not_left_as_a_complete_run(scenes, tmp_path):
    sim = frontier.load(scenes / "pendulum.yaml")
    path, stats = tmp_path / "interrupted.csv", tmp_path / "interrupted.json"
    with pytest.raises(RuntimeError, match="stop here"):
        with sim.record(trajectory=str(path), stats=str(stats)):
            sim.step(20)
            raise RuntimeError("stop here")
    # Nothing under the name of a complete run; the rows kept under NAME.failed.csv, the stats say
    # the run did not complete and why; no temporary files.
    assert not path.exists()
    failed = tmp_path / "interrupted.failed.csv"
    assert failed.is_file()
    assert max(read_trajectory(failed)) == pytest.approx(20 * sim.dt)
    summary = json.loads(stats.read_text())
    assert summary["completed"] is False
    assert "stop here" in json.dumps(summary)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["interrupted.failed.csv", "interrupted.json"]
    # Stepping on after the recording ended writes nothing more.
    before = failed.read_text()
    sim.step(5)
    assert failed.read_text() == before


def test_the_python_frame_is_the_frame_frontier_render_draws(scenes, tmp_path, frontier_cli):
    """The initial state rendered from Python and by `frontier render` at the same size: the same
    renderer and camera (the scene's: an automatic one is framed around one state in Python and
    around the whole run by `frontier render`) give the same pixels."""
    scene = scenes / "pendulum.yaml"
    sim = frontier.load(scene)
    image = sim.render(320, 240)
    path = tmp_path / "t.csv"
    with sim.record(trajectory=str(path)):
        sim.step(100)
    frames = tmp_path / "frames"
    done = frontier_cli("render", path, "--frames", frames, "--width", 320, "--height", 240, "--quiet")
    assert done.returncode == 0, done.stderr
    first = read_png(sorted(frames.glob("*.png"))[0])
    assert first.shape == image.shape
    assert np.array_equal(first, image), "%.4f of the pixels differ" % np.any(first != image, axis=2).mean()


def test_record_takes_path_objects_as_load_does(scenes, tmp_path):
    sim = frontier.load(scenes / "pendulum.yaml")
    with sim.record(trajectory=tmp_path / "p.csv", stats=tmp_path / "p.json"):
        sim.step(10)
    assert (tmp_path / "p.csv").is_file() and (tmp_path / "p.json").is_file()


def test_a_bad_record_request_fails_before_any_step_and_writes_nothing(scenes, tmp_path):
    sim = frontier.load(scenes / "pendulum.yaml")
    with pytest.raises(ValueError):
        sim.record(trajectory=str(tmp_path / "t.csv"), every=0)
    # A folder that cannot be made (a file is in the way) is an OSError naming the path.
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(OSError) as caught:
        sim.record(trajectory=str(blocker / "t.csv"))
    assert "file" in str(caught.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]
    assert sim.steps_taken == 0
