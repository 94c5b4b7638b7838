"""get_state / set_state rewinds a simulation: the same steps from a restored state give
bit-identical states (np.array_equal, not allclose), through contacts and joints."""
import threading
import sys

import frontier
import numpy as np
import pytest

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
