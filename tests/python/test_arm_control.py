"""A PD controller written in Python drives the bundled six-joint arm (effort actuators on its
shoulder and elbow, arm_effort.yaml) along a smooth move to a target; it tracks the move within a
bound, and settles where the built-in position servo with the same gains settles (arm_servo.yaml),
which is where the servo's torque balances gravity's about the joint, computed here from the URDF's
masses and the links' positions."""
import math
import pathlib
import xml.etree.ElementTree as ElementTree

import frontier
import numpy as np
import pytest

JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"]
GOAL = np.array([0.5, 0.6, 0.9])  # rad, the URDF's joint positions
KP = 2000.0  # N m/rad, as arm_servo.yaml
KD = 100.0  # N m s/rad
EFFORT_LIMIT = 100.0  # N m, the URDF's <limit effort>
MOVE = 1.5  # s, the length of the move
SETTLE = 1.5  # s after it
FRICTION = 0.2  # N m, the URDF's joint friction


def target(t):
    """Joint targets (rad) and their rates (rad/s) at time t: a cosine ramp from 0 to GOAL."""
    u = min(t / MOVE, 1.0)
    position = GOAL * (0.5 - 0.5 * math.cos(math.pi * u))
    rate = GOAL * (0.5 * math.pi / MOVE * math.sin(math.pi * u)) if u < 1.0 else np.zeros(3)
    return position, rate


def coordinates(sim):
    return [sim.coordinate_names.index(name) for name in JOINTS]


def actuators(sim):
    return [sim.actuator_names.index(name) for name in JOINTS]


def run_python_pd(here):
    sim = frontier.load(here / "arm_effort.yaml")
    q_index, a_index = coordinates(sim), actuators(sim)
    largest_error = 0.0
    while sim.time < MOVE + SETTLE - 1e-9:
        q = sim.joint_positions[q_index]
        qd = sim.joint_velocities[q_index]
        q_target, qd_target = target(sim.time)
        largest_error = max(largest_error, float(np.max(np.abs(q - q_target))))
        torque = np.clip(KP * (q_target - q) + KD * (qd_target - qd), -EFFORT_LIMIT, EFFORT_LIMIT)
        for a, value in zip(a_index, torque):
            sim.set_actuator_target(a, float(value))
        sim.step()
        # An effort actuator applies what it was given.
        np.testing.assert_allclose(sim.actuator_efforts[a_index], torque, rtol=1e-12, atol=1e-12)
    return sim, largest_error


def run_servo(here):
    sim = frontier.load(here / "arm_servo.yaml")
    a_index = actuators(sim)
    targets = np.zeros(len(sim.actuator_names))
    while sim.time < MOVE + SETTLE - 1e-9:
        targets[a_index] = target(sim.time)[0]
        for name, value in zip(JOINTS, targets[a_index]):
            sim.set_actuator_target(name, float(value))
        sim.step()
    return sim


def test_the_effort_scene_has_what_the_controller_needs(here):
    sim = frontier.load(here / "arm_effort.yaml")
    for name in JOINTS:
        assert name in sim.coordinate_names
        assert name in sim.actuator_names
    # hold: true put servos on the wrist joints too.
    assert {"wrist_1_joint", "wrist_2_joint", "wrist_3_joint"} <= set(sim.actuator_names)
    assert sim.joint_positions.shape == (len(sim.coordinate_names),)
    np.testing.assert_allclose(sim.joint_positions, 0.0, atol=1e-12)


def test_a_python_pd_controller_tracks_and_settles_where_the_servo_does(here):
    pd, largest_error = run_python_pd(here)
    servo = run_servo(here)
    q_pd = pd.joint_positions[coordinates(pd)]
    q_servo = servo.joint_positions[coordinates(servo)]
    print("python PD: largest tracking error %.4f rad, final error %s rad; servo final error %s rad"
          % (largest_error, np.round(q_pd - GOAL, 5), np.round(q_servo - GOAL, 5)))
    # Both track the move and end near the goal, at rest.
    assert largest_error < 0.05
    np.testing.assert_allclose(q_pd, GOAL, atol=0.03)
    np.testing.assert_allclose(q_servo, GOAL, atol=0.03)
    np.testing.assert_allclose(pd.joint_velocities[coordinates(pd)], 0.0, atol=1e-3)
    np.testing.assert_allclose(servo.joint_velocities[coordinates(servo)], 0.0, atol=1e-3)
    # With the same stiffness both hold the same sag against gravity: the same resting pose
    # (the joints' friction of 0.2 N m lets each stop within 0.2 / kp of it).
    np.testing.assert_allclose(q_pd, q_servo, atol=2 * FRICTION / KP + 1e-5)
    # The sag is real (the test would pass trivially without gravity): the leaning arm pulls its
    # shoulder lift measurably past its goal.
    assert abs(q_pd[1] - GOAL[1]) > 0.005


def urdf_masses(repo):
    path = repo / "scenes" / "robots" / "arm6_description" / "urdf" / "arm6.urdf"
    masses = {}
    for link in ElementTree.parse(path).getroot().iter("link"):
        mass = link.find("inertial/mass")
        masses[link.get("name")] = float(mass.get("value")) if mass is not None else 0.0
    return masses


def rotation_z(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_the_servo_torque_at_rest_balances_gravity_about_the_shoulder(here, repo):
    sim = run_servo(here)
    masses = urdf_masses(repo)
    names = sim.body_names
    # The links beyond the shoulder lift joint; the gripper (and the frames without mass) are
    # welded to the last wrist link unless the model keeps them as bodies of their own.
    outboard = {name: masses[name] for name in
                ["upper_arm_link", "forearm_link", "wrist_1_link", "wrist_2_link", "wrist_3_link"]}
    if "gripper_link" in names:
        outboard["gripper_link"] = masses["gripper_link"]
    else:
        outboard["wrist_3_link"] += masses["gripper_link"]
    assert sum(outboard.values()) == pytest.approx(13.89)
    # The shoulder link's centre is its frame's origin, 0.089 m above the base (the world's origin).
    np.testing.assert_allclose(sim.positions[names.index("shoulder_link")], [0, 0, 0.089], atol=1e-4)
    # The lift joint: 0.136 m along the shoulder's y, its axis that y, turned by the pan angle.
    pan = sim.joint_positions[sim.coordinate_names.index("shoulder_pan_joint")]
    turn = rotation_z(pan)
    anchor = np.array([0.0, 0.0, 0.089]) + turn @ np.array([0.0, 0.136, 0.0])
    axis = turn @ np.array([0.0, 1.0, 0.0])
    gravity = np.asarray(sim.gravity)
    gravity_torque = sum(
        np.cross(sim.positions[names.index(name)] - anchor, mass * gravity) @ axis
        for name, mass in outboard.items()
    )
    lift = sim.actuator_names.index("shoulder_lift_joint")
    effort = sim.actuator_efforts[lift]
    print("shoulder lift at rest: servo %.3f N m, gravity %.3f N m" % (effort, gravity_torque))
    assert abs(gravity_torque) > 10.0  # the arm leans: gravity pulls hard on the shoulder
    assert effort + gravity_torque == pytest.approx(0.0, abs=FRICTION + 0.01 * abs(gravity_torque))
    # The servo's torque is its spring's: kp times how far the joint sags from its target.
    q = sim.joint_positions[sim.coordinate_names.index("shoulder_lift_joint")]
    assert effort == pytest.approx(KP * (GOAL[1] - q), rel=0.01)
    # Gravity has no moment about the vertical pan axis: its servo carries only friction.
    assert abs(sim.actuator_efforts[sim.actuator_names.index("shoulder_pan_joint")]) <= FRICTION + 1e-6


def test_hold_servos_of_a_bare_urdf_reach_targets_set_from_python(repo):
    sim = frontier.load(repo / "scenes" / "robots" / "arm6_description" / "urdf" / "arm6.urdf",
                        fixed_base=True, hold=True)
    coordinates_of = [sim.coordinate_names.index(name) for name in JOINTS]
    # Targets as a whole array, in actuator order.
    targets = np.zeros(len(sim.actuator_names))
    while sim.time < MOVE + SETTLE - 1e-9:
        for name, value in zip(JOINTS, target(sim.time)[0]):
            targets[sim.actuator_names.index(name)] = value
        sim.set_actuator_targets(targets)
        sim.step()
    q = sim.joint_positions[coordinates_of]
    print("hold servos: final error %s rad" % np.round(q - GOAL, 5))
    np.testing.assert_allclose(q, GOAL, atol=0.05)
    np.testing.assert_allclose(sim.joint_velocities, 0.0, atol=1e-3)
    # An array of the wrong length is refused.
    with pytest.raises(ValueError):
        sim.set_actuator_targets(np.zeros(len(sim.actuator_names) + 1))
