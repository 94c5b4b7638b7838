"""The bundled pendulum (scenes/pendulum.yaml: a 1 kg ball of radius 0.05 m on a 1 m hinge from
(0, 0, 2), released at 60 degrees) stepped from a Python loop swings with the exact large-angle
period, T = 4 sqrt(I / (m g d)) K(sin(theta0 / 2)), K computed here by the arithmetic-geometric mean."""
import math

import frontier
import numpy as np
import pytest

PIVOT = np.array([0.0, 0.0, 2.0])  # m, the hinge's anchor in the scene
LENGTH = 1.0  # m, pivot to the ball's centre
RADIUS = 0.05  # m
MASS = 1.0  # kg
THETA0 = math.radians(60.0)


def agm(a, b):
    while abs(a - b) > 1e-15 * a:
        a, b = (a + b) / 2.0, math.sqrt(a * b)
    return a


def elliptic_k(k):
    """Complete elliptic integral of the first kind, modulus k: pi / (2 AGM(1, sqrt(1 - k^2)))."""
    return math.pi / (2.0 * agm(1.0, math.sqrt(1.0 - k * k)))


def test_elliptic_k_known_values():
    assert elliptic_k(0.0) == pytest.approx(math.pi / 2, rel=1e-15)
    # K(1/sqrt 2) = Gamma(1/4)^2 / (4 sqrt(pi))
    assert elliptic_k(math.sqrt(0.5)) == pytest.approx(math.gamma(0.25) ** 2 / (4 * math.sqrt(math.pi)), rel=1e-14)


def test_period_from_a_python_step_loop(scenes):
    sim = frontier.load(scenes / "pendulum.yaml")
    bob = sim.body_names.index("bob")
    g = float(np.linalg.norm(sim.gravity))
    assert g == pytest.approx(9.81)
    start = sim.positions[bob] - PIVOT
    assert np.linalg.norm(start) == pytest.approx(LENGTH, abs=1e-12)
    assert math.atan2(start[0], -start[2]) == pytest.approx(THETA0, abs=1e-12)

    # A solid ball: its own inertia about its centre adds to m d^2 about the pivot.
    inertia = MASS * LENGTH**2 + 0.4 * MASS * RADIUS**2
    exact = 4.0 * math.sqrt(inertia / (MASS * g * LENGTH)) * elliptic_k(math.sin(THETA0 / 2.0))
    small_angle = 2.0 * math.pi * math.sqrt(inertia / (MASS * g * LENGTH))
    assert exact > 1.07 * small_angle  # 60 degrees is far from the small-angle regime

    # Zero crossings of the ball's x (the pivot's x is 0), linearly interpolated, over 10 s.
    crossings = []
    previous_time, previous_x = sim.time, sim.positions[bob, 0]
    while sim.time < 10.0:
        sim.step()
        x = sim.positions[bob, 0]
        if (previous_x > 0.0) != (x > 0.0):
            crossings.append(previous_time + (sim.time - previous_time) * previous_x / (previous_x - x))
        previous_time, previous_x = sim.time, x
    assert sim.steps_taken == 10000
    assert len(crossings) >= 8
    measured = 2.0 * (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    relative = (measured - exact) / exact
    print("pendulum from Python: period %.6f s, exact %.6f s, relative error %.3g" % (measured, exact, relative))
    assert abs(relative) < 0.005
    # Half periods agree with each other: the swing neither grows nor decays much in 10 s.
    halves = np.diff(crossings)
    assert np.ptp(halves) < 0.01 * exact
    # And the hinge holds the length.
    assert np.linalg.norm(sim.positions[bob] - PIVOT) == pytest.approx(LENGTH, abs=1e-6)
