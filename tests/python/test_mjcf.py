"""MJCF files load from Python as `frontier run` loads them: keyframes, actuators in joint units and
MuJoCo's compiler errors as LoadErrors at the file's line."""
import math

import frontier
import numpy as np
import pytest

# A rod turning about a vertical hinge (gravity does not act on its angle), driven by a position
# actuator of gear 2, and a key that starts it at 0.3 rad with control 0.4 (target 0.4 / 2 rad).
TURNTABLE = """\
<mujoco model="turntable">
  <compiler angle="radian"/>
  <option timestep="0.001"/>
  <worldbody>
    <body name="rod" pos="0 0 1">
      <joint name="spin" type="hinge" axis="0 0 1" damping="0.5"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.02" density="1000"/>
    </body>
  </worldbody>
  <actuator>
    <position name="servo" joint="spin" kp="5" gear="2"/>
  </actuator>
  <keyframe>
    <key name="tilted" qpos="0.3" ctrl="0.4"/>
  </keyframe>
</mujoco>
"""


def write(tmp_path, text, name="model.xml"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_a_keyframe_sets_the_start_and_the_servo_target_in_joint_units(tmp_path):
    sim = frontier.load(write(tmp_path, TURNTABLE), keyframe="tilted")
    assert list(sim.coordinate_names) == ["spin"]
    assert sim.joint_positions[0] == pytest.approx(0.3, abs=1e-12)
    # The rod's far end where a turn of 0.3 rad about z puts it: its centre of mass at 0.25 m.
    rod = list(sim.body_names).index("rod")
    np.testing.assert_allclose(sim.positions[rod], [0.25 * math.cos(0.3), 0.25 * math.sin(0.3), 1.0], atol=1e-9)
    sim.step(20000)  # 20 s: the servo (kp 5 x gear^2 = 20 N m/rad) settles at ctrl / gear = 0.2 rad
    assert sim.joint_positions[0] == pytest.approx(0.2, abs=1e-6)


def test_without_a_keyframe_it_starts_in_the_reference_pose(tmp_path):
    sim = frontier.load(write(tmp_path, TURNTABLE))
    assert sim.joint_positions[0] == 0.0
    sim.set_actuator_target("spin", -0.1)
    sim.step(20000)
    assert sim.joint_positions[0] == pytest.approx(-0.1, abs=1e-6)


def test_an_unknown_keyframe_names_the_known_ones(tmp_path):
    with pytest.raises(frontier.LoadError) as caught:
        frontier.load(write(tmp_path, TURNTABLE), keyframe="tilt")
    assert "'tilted'" in str(caught.value)


def test_the_compilers_error_is_a_load_error_at_its_line(tmp_path):
    bad = TURNTABLE.replace('<geom type="capsule"', '<geom type="capsule" colour="red"')
    path = write(tmp_path, bad)
    with pytest.raises(frontier.LoadError) as caught:
        frontier.load(path)
    assert caught.value.file == path
    assert caught.value.line == 7
    assert "colour" in caught.value.message
