"""What a user can get wrong is refused with a clear exception, never a crash or a silent loss:
recordings that would replace an input, a simulator read while another thread steps it, a state of
another file, a dropped recording, half-applied targets, images and cameras that make no sense."""
import gc
import shutil
import threading

import frontier
import numpy as np
import pytest

from conftest import REPO

PENDULUM = REPO / "scenes" / "pendulum.yaml"
PILEUP = REPO / "scenes" / "pileup44.yaml"


def test_a_recording_never_replaces_the_scene_it_loaded(tmp_path):
    scene = tmp_path / "p.yaml"
    shutil.copy(PENDULUM, scene)
    before = scene.read_bytes()
    sim = frontier.load(scene)
    with pytest.raises(ValueError, match="is the input"):
        sim.record(trajectory=scene)
    with pytest.raises(ValueError, match="same file"):
        sim.record(trajectory=tmp_path / "same.out", stats=tmp_path / "same.out")
    assert scene.read_bytes() == before
    assert not (tmp_path / "same.out").exists()
    with sim.record(trajectory=tmp_path / "ok.csv"):  # refusals left no recording behind
        sim.step(3)
    assert (tmp_path / "ok.csv").exists()


def test_a_recording_is_written_where_its_name_pointed_when_it_began(tmp_path, monkeypatch):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    monkeypatch.chdir(tmp_path / "a")
    sim = frontier.load(PENDULUM)
    recording = sim.record(trajectory="rel.csv")
    sim.step(2)
    monkeypatch.chdir(tmp_path / "b")
    recording.close()
    assert (tmp_path / "a" / "rel.csv").exists() and not (tmp_path / "b" / "rel.csv").exists()


def test_a_dropped_recording_writes_nothing_and_frees_the_simulator(tmp_path):
    sim = frontier.load(PENDULUM)
    start = sim.get_state()
    sim.record(trajectory=tmp_path / "dropped.csv")  # the handle is not kept
    gc.collect()
    sim.step(5)
    sim.set_state(start)  # no recording is under way any more
    with sim.record(trajectory=tmp_path / "kept.csv"):
        sim.step(5)
    assert not (tmp_path / "dropped.csv").exists()
    assert (tmp_path / "kept.csv").exists()


def test_reading_a_simulator_while_another_thread_steps_it_raises_instead_of_crashing():
    sim = frontier.load(PILEUP)
    errors = []
    stepping = threading.Event()

    def run():
        stepping.set()
        for _ in range(200):
            sim.step(5)

    thread = threading.Thread(target=run)
    thread.start()
    stepping.wait()
    reads = 0
    while thread.is_alive():
        for read in (lambda: sim.contacts, lambda: sim.joint_wrenches, sim.get_state, lambda: sim.positions):
            try:
                read()
                reads += 1
            except RuntimeError as error:
                assert "busy in another thread" in str(error)
                errors.append(error)
    thread.join()
    assert errors, "no read overlapped a step: the test proved nothing"
    assert np.all(np.isfinite(sim.positions))  # and the simulator is whole afterwards
    sim.step()


def test_a_state_of_another_file_is_refused_even_with_the_same_sizes(tmp_path):
    copy = tmp_path / "pendulum_copy.yaml"
    shutil.copy(PENDULUM, copy)
    original = frontier.load(PENDULUM)
    other = frontier.load(copy)
    with pytest.raises(ValueError, match="a state of"):
        other.set_state(original.get_state())
    twin = frontier.load(PENDULUM)
    twin.set_state(original.get_state())  # the same file: accepted


def test_set_actuator_targets_sets_none_when_one_is_bad():
    sim = frontier.load(REPO / "scenes" / "robots" / "quadruped_stand.yaml")
    start = sim.get_state()
    values = np.zeros(len(sim.actuator_names))
    values[0] = 0.8
    values[1] = np.nan
    with pytest.raises(ValueError, match="must be finite"):
        sim.set_actuator_targets(values)
    sim.step(200)
    after_refusal = sim.joint_positions
    fresh = frontier.load(REPO / "scenes" / "robots" / "quadruped_stand.yaml")
    fresh.set_state(start)
    fresh.step(200)
    assert np.array_equal(after_refusal, fresh.joint_positions)  # the 0.8 was not applied


def test_indices_of_the_wrong_type_and_range_say_so():
    sim = frontier.load(PENDULUM)
    with pytest.raises(TypeError, match="expected a name"):
        sim.apply_force(1.5, [0, 0, 1])
    with pytest.raises(IndexError, match="out of range"):
        sim.apply_force(2**40, [0, 0, 1])
    sim.apply_force(np.int64(0), [0, 0, 1])  # numpy integers are indices


def test_images_must_be_uint8_and_cameras_must_make_sense(tmp_path):
    with pytest.raises(ValueError, match="uint8"):
        frontier.write_png(tmp_path / "f.png", np.ones((4, 4, 3)) * 0.9)
    with pytest.raises(OSError):
        frontier.read_png(tmp_path / "missing.png")
    sim = frontier.load(PENDULUM)
    for camera in ({}, dict(position=(1, 1, 1), look_at=(1, 1, 1)),
                   dict(position=(3, 0, 1), look_at=(0, 0, 1), fov=0),
                   dict(position=(3, 0, 1), look_at=(0, 0, 1), fov=float("nan"))):
        with pytest.raises(ValueError):
            sim.render(32, 24, camera=camera)


def test_the_automatic_camera_stays_where_the_first_render_framed_it(tmp_path):
    sim = frontier.load(REPO / "scenes" / "falling_doll.yaml")
    sim.render(80, 60)
    sim.step(300)
    first = sim.render(80, 60)
    sim.render(81, 60)
    sim.render(80, 60, camera=dict(position=(3, 3, 3), look_at=(0, 0, 0)))
    again = sim.render(80, 60)
    assert np.array_equal(first, again)


def test_names_that_are_not_utf8_come_back_escaped(tmp_path):
    scene = tmp_path / "latin1.yaml"
    scene.write_bytes(PENDULUM.read_bytes().replace(b"name: bob", b"name: caf\xe9").replace(b"child: bob", b"child: caf\xe9"))
    sim = frontier.load(scene)
    assert "caf\\xe9" in sim.body_names
