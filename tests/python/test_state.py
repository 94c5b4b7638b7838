"""get_state / set_state rewinds a simulation: the same steps from a restored state give
bit-identical states (np.array_equal, not allclose), through contacts and joints."""
import threading
import sys

import frontier
import numpy as np
import pytest

from frontier_testing import read_trajectory

QUANTITIES = ("positions", "orientations", "velocities", "angular_velocities", "joint_positions",
              "joint_velocities")


def snapshot(sim):
    return {name: getattr(sim, name) for name in QUANTITIES}


def rollout(sim, steps):
    """The state after each of `steps` steps."""
    states = []
    for _ in range(steps):
        sim.step()
        states.append(snapshot(sim))
    return states


def assert_identical(first, second):
    assert len(first) == len(second)
    for k, (a, b) in enumerate(zip(first, second)):
        for name in QUANTITIES:
            assert np.array_equal(a[name], b[name]), "%s differs after step %d" % (name, k + 1)


@pytest.mark.parametrize("scene,k,m", [("falling_doll.yaml", 400, 300), ("pileup44.yaml", 300, 200)])
def test_restore_then_the_same_steps_are_bit_identical(scenes, scene, k, m):
    sim = frontier.load(scenes / scene)
    sim.step(k)  # into the contacts: the doll lands at about 0.4 s, the pile starts at once
    saved = sim.get_state()
    time, steps = sim.time, sim.steps_taken
    first = rollout(sim, m)
    assert len(sim.contacts) > 0  # the rollout went through contacts
    assert not np.array_equal(first[0]["positions"], first[-1]["positions"])  # and moved
    sim.set_state(saved)
    assert sim.time == time and sim.steps_taken == steps
    assert_identical(first, rollout(sim, m))
    # A state can be restored more than once.
    sim.set_state(saved)
    assert_identical(first, rollout(sim, m))


def test_a_state_restores_into_another_simulator_of_the_same_scene(scenes):
    sim = frontier.load(scenes / "falling_doll.yaml")
    sim.step(450)
    saved = sim.get_state()
    first = rollout(sim, 100)
    other = frontier.load(scenes / "falling_doll.yaml")
    other.set_state(saved)
    assert_identical(first, rollout(other, 100))


def test_restore_undoes_changes_made_after_the_save(scenes):
    sim = frontier.load(scenes / "falling_doll.yaml")
    sim.step(100)
    saved = sim.get_state()
    first = rollout(sim, 50)
    sim.set_state(saved)
    sim.apply_force("pelvis", [500.0, 0.0, 0.0])
    pushed = rollout(sim, 50)
    assert not np.array_equal(first[-1]["positions"], pushed[-1]["positions"])
    sim.set_state(saved)
    assert_identical(first, rollout(sim, 50))


def test_the_initial_state_restores_a_fresh_run(scenes):
    sim = frontier.load(scenes / "pileup44.yaml")
    start = sim.get_state()
    first = rollout(sim, 60)
    sim.set_state(start)
    assert sim.time == 0.0
    assert_identical(first, rollout(sim, 60))
    fresh = frontier.load(scenes / "pileup44.yaml")
    assert_identical(first, rollout(fresh, 60))


def test_a_state_of_another_scene_is_refused(scenes):
    doll = frontier.load(scenes / "falling_doll.yaml")
    pendulum = frontier.load(scenes / "pendulum.yaml")
    with pytest.raises((ValueError, TypeError)):
        pendulum.set_state(doll.get_state())
    pendulum.step(10)
    assert np.all(np.isfinite(pendulum.positions))


def test_arrays_are_copies_that_stepping_does_not_change(scenes):
    sim = frontier.load(scenes / "pendulum.yaml")
    before = sim.positions
    kept = before.copy()
    sim.step(100)
    assert np.array_equal(before, kept)
    assert not np.array_equal(sim.positions, kept)
    # Writing into a returned array does not move the body.
    after = sim.positions
    after[:] = 123.0
    assert not np.any(sim.positions == 123.0)


def test_step_releases_the_gil(scenes):
    """While one thread is inside sim.step(n), another runs Python. With a switch interval far
    longer than the run, a step that held the GIL would keep the waiting thread out until it ended."""
    sim = frontier.load(scenes / "pileup44.yaml")
    started, finished = threading.Event(), threading.Event()

    def worker():
        started.set()
        sim.step(1000)
        finished.set()

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        thread = threading.Thread(target=worker)
        thread.start()
        started.wait()
        ran_during_step = not finished.is_set()
        thread.join()
    finally:
        sys.setswitchinterval(interval)
    assert sim.steps_taken == 1000
    assert ran_during_step


def test_actuator_targets_and_pending_forces_are_part_of_the_state(scenes):
    sim = frontier.load(scenes / "robots" / "arm6_description" / "urdf" / "arm6.urdf", fixed_base=True,
                        hold=True)
    sim.set_actuator_target("elbow_joint", 0.4)
    sim.apply_force("forearm_link", [0.0, 30.0, 0.0])  # pending: acts in the next step
    saved = sim.get_state()
    assert saved.time == 0.0 and saved.steps_taken == 0
    first = rollout(sim, 200)
    sim.set_state(saved)
    sim.set_actuator_target("elbow_joint", -0.4)  # changed after the save ...
    sim.set_state(saved)  # ... and restored with it
    assert_identical(first, rollout(sim, 200))


def test_set_state_is_refused_while_recording(scenes, tmp_path):
    sim = frontier.load(scenes / "pendulum.yaml")
    saved = sim.get_state()
    with sim.record(trajectory=str(tmp_path / "t.csv")):
        sim.step(10)
        with pytest.raises(RuntimeError):
            sim.set_state(saved)  # the recorded rows would run back in time
        sim.step(10)
    assert sim.steps_taken == 20
    assert max(read_trajectory(tmp_path / "t.csv")) == pytest.approx(20 * sim.dt)
