"""The state arrays: shapes, dtypes and layout; values equal to what `frontier run` writes for the
same steps (its CSV holds 17 significant digits, so they must match exactly); units and conventions
checked against mechanics worked out here."""
import math

import frontier
import numpy as np
import pytest

from frontier_testing import read_trajectory, write_scene


def assert_array(value, shape, dtype=np.float64):
    assert isinstance(value, np.ndarray)
    assert value.shape == shape
    assert value.dtype == dtype
    assert value.flags["C_CONTIGUOUS"]


def test_shapes_dtypes_and_names(scenes):
    sim = frontier.load(scenes / "falling_doll.yaml")
    sim.step(5)
    n = len(sim.body_names)
    assert n == len(set(sim.body_names)) and "pelvis" in sim.body_names and "floor" in sim.body_names
    for name in ("positions", "velocities", "angular_velocities"):
        assert_array(getattr(sim, name), (n, 3))
    assert_array(sim.orientations, (n, 4))
    assert_array(sim.is_static, (n,), np.bool_)
    assert sim.is_static[sim.body_names.index("floor")]
    assert not sim.is_static[sim.body_names.index("pelvis")]
    k = len(sim.coordinate_names)
    assert k > 0
    assert_array(sim.joint_positions, (k,))
    assert_array(sim.joint_velocities, (k,))
    assert_array(sim.joint_wrenches, (len(sim.joint_names), 6))
    assert_array(sim.actuator_efforts, (len(sim.actuator_names),))
    assert_array(np.asarray(sim.gravity), (3,))
    assert isinstance(sim.time, float) and isinstance(sim.dt, float)
    assert sim.time == 5 * sim.dt
    assert isinstance(sim.energy, float)
    contacts = sim.contacts
    assert isinstance(contacts, np.ndarray)
    for field, dtype, shape in (("body_a", np.int32, ()), ("body_b", np.int32, ()), ("point", np.float64, (3,)),
                                ("normal", np.float64, (3,)), ("depth", np.float64, ()),
                                ("force", np.float64, (3,))):
        assert contacts.dtype[field].base == dtype, field
        assert contacts.dtype[field].shape == shape, field


@pytest.mark.parametrize("scene,steps", [("falling_doll.yaml", 700), ("pileup44.yaml", 250)])
def test_state_equals_the_trajectory_csv_of_frontier_run(scenes, tmp_path, frontier_cli, scene, steps):
    csv = tmp_path / "run.csv"
    done = frontier_cli("run", scenes / scene, "--steps", steps, "--trajectory", csv)
    assert done.returncode == 0, done.stderr
    rows = read_trajectory(csv)
    sim = frontier.load(scenes / scene)
    sim.step(steps)
    last = max(rows)
    assert last == sim.time  # both count time as steps * dt
    recorded = rows[last]
    moving = [i for i, static in enumerate(sim.is_static) if not static]
    assert sorted(recorded) == sorted(sim.body_names[i] for i in moving)
    for i in moving:
        expected = np.array(recorded[sim.body_names[i]])
        assert np.array_equal(sim.positions[i], expected[0:3]), sim.body_names[i]
        assert np.array_equal(sim.orientations[i], expected[3:7]), sim.body_names[i]  # w first, as the CSV
        assert np.array_equal(sim.velocities[i], expected[7:10]), sim.body_names[i]
        assert np.array_equal(sim.angular_velocities[i], expected[10:13]), sim.body_names[i]


def test_orientations_are_unit_with_w_first(scenes):
    """The pendulum's ball turns with its hinge (axis +y): after the swing its orientation is the
    rotation about y by the angle its centre has swept about the pivot, w = cos(angle / 2) first."""
    sim = frontier.load(scenes / "pendulum.yaml")
    bob = sim.body_names.index("bob")
    pivot = np.array([0.0, 0.0, 2.0])
    start = sim.positions[bob] - pivot
    np.testing.assert_array_equal(sim.orientations[bob], [1.0, 0.0, 0.0, 0.0])
    sim.step(300)
    now = sim.positions[bob] - pivot
    # The signed angle from start to now about +y.
    swept = math.atan2(np.cross(start, now) @ [0.0, 1.0, 0.0], start @ now)
    assert abs(swept) > 0.3
    q = sim.orientations[bob]
    assert np.linalg.norm(q) == pytest.approx(1.0, abs=1e-12)
    q = q if q[0] >= 0 else -q
    np.testing.assert_allclose(q, [math.cos(swept / 2), 0.0, math.sin(swept / 2), 0.0], atol=1e-6)
    # The hinge's coordinate is the same angle (0 at the initial pose), its rate the ball's spin.
    assert sim.coordinate_names == ["pivot"]
    assert sim.joint_positions[0] == pytest.approx(swept, abs=1e-6)
    assert sim.joint_velocities[0] == pytest.approx(sim.angular_velocities[bob][1], abs=1e-9)
    for name in ("falling_doll.yaml", "pileup44.yaml"):
        other = frontier.load(scenes / name)
        other.step(300)
        np.testing.assert_allclose(np.linalg.norm(other.orientations, axis=1), 1.0, atol=1e-12)


BOX_ON_FLOOR = """\
name: box on the floor
simulation: {dt: 0.001, duration: 2.0, gravity: [0, 0, -9.81], solver: linear}
bodies:
  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1], offset: 0}}
  - {name: box, shape: {type: box, size: [0.4, 0.3, 0.2]}, mass: 2.5, position: [0.3, -0.2, 0.1]}
"""


def test_contacts_of_a_box_at_rest_carry_its_weight(tmp_path):
    sim = frontier.load(write_scene(tmp_path, "box.yaml", BOX_ON_FLOOR))
    sim.step(1000)
    box = sim.body_names.index("box")
    assert np.linalg.norm(sim.velocities[box]) < 1e-5  # at rest (m/s)
    contacts = sim.contacts
    assert len(contacts) >= 3  # a face on a plane: at least three points hold it level
    on_box = np.zeros(3)
    for c in contacts:
        assert {int(c["body_a"]), int(c["body_b"])} == {box, sim.body_names.index("floor")}
        assert np.linalg.norm(c["normal"]) == pytest.approx(1.0, abs=1e-12)
        assert abs(c["depth"]) < 1e-3  # m: touching, not sunk
        assert c["point"][2] == pytest.approx(0.0, abs=1e-3)
        # The points lie under the box's footprint (0.4 x 0.3 m about (0.3, -0.2)).
        assert abs(c["point"][0] - 0.3) <= 0.2 + 1e-6 and abs(c["point"][1] + 0.2) <= 0.15 + 1e-6
        # The force is on body_b; the normal points from a to b, and contact only pushes.
        on_box += c["force"] if c["body_b"] == box else -c["force"]
        assert c["force"] @ c["normal"] >= -1e-9
    weight = 2.5 * 9.81
    assert on_box[2] == pytest.approx(weight, rel=0.01)
    assert abs(on_box[0]) < 0.01 * weight and abs(on_box[1]) < 0.01 * weight


BALL_IN_SPACE = """\
name: a ball in space
simulation: {dt: 0.001, duration: 1.0, gravity: [0, 0, 0], solver: linear}
bodies:
  - {name: ball, shape: {type: sphere, radius: 0.2}, mass: 4.0, position: [0, 0, 5]}
"""


def test_a_force_and_torque_act_for_one_step_in_si_units(tmp_path):
    sim = frontier.load(write_scene(tmp_path, "ball.yaml", BALL_IN_SPACE))
    ball = sim.body_names.index("ball")
    mass, inertia = 4.0, 0.4 * 4.0 * 0.2**2  # kg, kg m^2 (a solid ball)
    force, torque = np.array([8.0, -2.0, 4.0]), np.array([0.0, 0.3, -0.1])
    sim.apply_force("ball", force, torque=torque)
    sim.step()
    np.testing.assert_allclose(sim.velocities[ball], force * sim.dt / mass, rtol=1e-12)
    np.testing.assert_allclose(sim.angular_velocities[ball], torque * sim.dt / inertia, rtol=1e-9, atol=1e-15)
    # Only for that step: the ball then coasts.
    velocity = sim.velocities[ball]
    sim.step(10)
    np.testing.assert_allclose(sim.velocities[ball], velocity, rtol=1e-12)


def test_a_force_off_the_centre_also_turns_the_body(tmp_path):
    sim = frontier.load(write_scene(tmp_path, "ball.yaml", BALL_IN_SPACE))
    ball = sim.body_names.index("ball")
    inertia = 0.4 * 4.0 * 0.2**2
    force = np.array([0.0, 0.0, 10.0])
    point = sim.positions[ball] + [0.2, 0.0, 0.0]  # world frame, on the ball's +x side
    sim.apply_force(ball, force, point=point)
    sim.step()
    np.testing.assert_allclose(sim.velocities[ball], force * sim.dt / 4.0, rtol=1e-12)
    # torque = r x F = (0.2, 0, 0) x (0, 0, 10) = (0, -2, 0)
    np.testing.assert_allclose(sim.angular_velocities[ball], [0.0, -2.0 * sim.dt / inertia, 0.0], rtol=1e-9,
                               atol=1e-15)


def test_gravity_is_settable_in_metres_per_second_squared(tmp_path):
    sim = frontier.load(write_scene(tmp_path, "ball.yaml", BALL_IN_SPACE))
    np.testing.assert_array_equal(sim.gravity, [0.0, 0.0, 0.0])
    sim.gravity = [0.0, 3.0, -9.81]
    np.testing.assert_array_equal(sim.gravity, [0.0, 3.0, -9.81])
    sim.step(200)
    ball = sim.body_names.index("ball")
    np.testing.assert_allclose(sim.velocities[ball], np.array([0.0, 3.0, -9.81]) * sim.time, rtol=1e-12)
    # Symplectic Euler: x(n) = x0 + g dt^2 n (n + 1) / 2.
    n = sim.steps_taken
    np.testing.assert_allclose(sim.positions[ball], [0.0, 0.0, 5.0] + np.array([0.0, 3.0, -9.81]) * sim.dt**2 * n * (n + 1) / 2,
                               rtol=1e-9)


def test_the_joint_wrench_of_a_hanging_ball_is_its_weight(tmp_path):
    scene = write_scene(tmp_path, "hanging.yaml", """\
name: hanging ball
simulation: {dt: 0.001, duration: 1.0, gravity: [0, 0, -9.81], solver: linear}
bodies:
  - {name: bob, shape: {type: sphere, radius: 0.05}, mass: 3.0, position: [0, 0, 1]}
joints:
  - {name: pivot, type: revolute, parent: world, child: bob, anchor: [0, 0, 2], axis: [0, 1, 0]}
""")
    sim = frontier.load(scene)
    sim.step(50)
    assert sim.joint_names == ["pivot"]
    np.testing.assert_allclose(sim.joint_wrenches[0, :3], [0.0, 0.0, 3.0 * 9.81], rtol=1e-6, atol=1e-9)


def test_energy_is_conserved_by_the_pendulum_and_joint_error_is_small(scenes):
    sim = frontier.load(scenes / "pendulum.yaml", integrator="rattle")
    bob = sim.body_names.index("bob")
    # At the release: all potential, m g z with the zero at z = 0 (or any constant).
    start = sim.energy
    sim.step(2000)
    kinetic = 0.5 * 1.0 * np.sum(sim.velocities[bob] ** 2) + 0.5 * (0.4 * 1.0 * 0.05**2) * np.sum(
        sim.angular_velocities[bob] ** 2)
    # The energy's change from the release equals the kinetic energy gained minus the height lost.
    assert sim.energy - start == pytest.approx(kinetic + 9.81 * (sim.positions[bob, 2] - 1.5), abs=1e-9)
    assert abs(sim.energy - start) < 1e-3 * 9.81 * 0.5
    position_error, angle_error = sim.joint_error
    assert 0.0 <= position_error < 1e-6 and 0.0 <= angle_error < 1e-6


def test_a_blow_up_is_a_simulation_error_naming_the_body(tmp_path):
    sim = frontier.load(write_scene(tmp_path, "ball.yaml", BALL_IN_SPACE))
    sim.step(3)
    sim.apply_force("ball", [4.0e13, 0.0, 0.0])  # 1e10 m/s in one step: past every range
    with pytest.raises(frontier.SimulationError) as caught:
        sim.step(10)
    error = caught.value
    assert isinstance(error, RuntimeError)
    assert error.body == "ball"
    assert error.step >= 4
    assert error.time == pytest.approx(error.step * sim.dt)
    assert error.quantity


def test_forces_before_one_step_add_up_and_static_bodies_refuse_them(tmp_path):
    sim = frontier.load(write_scene(tmp_path, "ball.yaml", BALL_IN_SPACE))
    ball = sim.body_names.index("ball")
    sim.apply_force(ball, [3.0, 0.0, 0.0])
    sim.apply_force("ball", [1.0, 2.0, 0.0])
    sim.step()
    np.testing.assert_allclose(sim.velocities[ball], np.array([4.0, 2.0, 0.0]) * sim.dt / 4.0, rtol=1e-12)
    floor = frontier.load(write_scene(tmp_path, "box.yaml", BOX_ON_FLOOR))
    with pytest.raises(ValueError):
        floor.apply_force("floor", [1.0, 0.0, 0.0])
    with pytest.raises(IndexError):
        floor.apply_force(len(floor.body_names), [1.0, 0.0, 0.0])
