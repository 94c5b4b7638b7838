"""Loading errors reach Python as exceptions that name the file, line and column of the fault, and
names a model lacks are KeyErrors that suggest the nearest one."""
import pathlib

import frontier
import numpy as np
import pytest

from frontier_testing import write_scene


def where(text, line_contains, token):
    """The 1-based line and column of `token` on the first line of `text` containing `line_contains`."""
    for number, line in enumerate(text.splitlines(), start=1):
        if line_contains in line:
            return number, line.index(token, line.index(line_contains)) + 1
    raise AssertionError("no line contains %r" % line_contains)


def assert_located(error, path, line, column):
    """A LoadError at path:line:column whose text says so as the command line does."""
    assert isinstance(error, frontier.LoadError)
    assert isinstance(error, ValueError)
    assert pathlib.Path(error.file).resolve() == pathlib.Path(path).resolve()
    assert (error.line, error.column) == (line, column), str(error)
    assert error.message and error.message in str(error)
    assert str(error).startswith("%s:%d:%d: error: " % (error.file, line, column)), str(error)


def test_a_missing_file_is_a_load_error_naming_it(tmp_path):
    missing = tmp_path / "no_such_scene.yaml"
    with pytest.raises(frontier.LoadError) as caught:
        frontier.load(str(missing))
    assert pathlib.Path(caught.value.file).resolve() == missing.resolve()
    assert "no_such_scene.yaml" in str(caught.value)
    # Not a line of the file: there is no file.
    assert caught.value.line in (0, None)


def test_a_missing_file_given_as_a_path_object(tmp_path):
    with pytest.raises(frontier.LoadError):
        frontier.load(tmp_path / "absent.urdf")


BAD_MASS = """\
# a ball whose mass is negative
name: bad mass
simulation: {dt: 0.001, duration: 1.0, gravity: [0, 0, -9.81]}
bodies:
  - name: ball
    shape: {type: sphere, radius: 0.1}
    position: [0, 0, 1]
    mass:   -2.5
"""


def test_a_bad_value_names_its_file_line_and_column(tmp_path):
    path = write_scene(tmp_path, "bad_mass.yaml", BAD_MASS)
    line, column = where(BAD_MASS, "mass:", "-2.5")
    assert (line, column) == (8, 13)
    with pytest.raises(frontier.LoadError) as caught:
        frontier.load(str(path))
    assert_located(caught.value, path, line, column)
    assert "mass" in caught.value.message


BALL = "bodies:\n  - {name: ball, shape: {type: sphere, radius: 0.1}, mass: 1, position: [0, 0, 1]}\n"
BAD_SCENES = {
    # a value of the wrong kind: a list where a number goes
    "bad_dt.yaml": ("name: bad step\nsimulation:\n  duration: 1.0\n  dt: [0.001]\n" + BALL, "dt:", "["),
    # a name the reader does not know
    "integrator.yaml": ("name: unknown integrator\nsimulation: {dt: 0.001, duration: 1.0, integrator: verlet}\n"
                        + BALL, "integrator:", "verlet"),
}


@pytest.mark.parametrize("name", sorted(BAD_SCENES))
def test_a_bad_setting_names_its_line_and_column(tmp_path, name):
    text, line_contains, token = BAD_SCENES[name]
    path = write_scene(tmp_path, name, text)
    with pytest.raises(frontier.LoadError) as caught:
        frontier.load(path)
    assert_located(caught.value, path, *where(text, line_contains, token))
    assert token in caught.value.message or token == "["


def test_an_unknown_integrator_keyword_is_a_load_error(scenes):
    with pytest.raises(frontier.LoadError) as caught:
        frontier.load(scenes / "pendulum.yaml", integrator="verlet")
    text = str(caught.value)
    assert "verlet" in text
    # The message lists what is allowed.
    for name in ("euler", "rattle"):
        assert name in text


@pytest.mark.parametrize("keyword", [dict(dt=-1.0), dict(dt=0.0), dict(solver="fast"), dict(pgs_iterations=0)])
def test_a_keyword_out_of_range_is_a_load_error(scenes, keyword):
    with pytest.raises(frontier.LoadError) as caught:
        frontier.load(scenes / "pendulum.yaml", **keyword)
    assert str(list(keyword.values())[0]) in str(caught.value) or "dt" in str(caught.value)


def test_the_same_scene_loads_with_every_known_integrator(scenes):
    for name in ("euler", "rattle", "rattle4"):
        sim = frontier.load(scenes / "pendulum.yaml", integrator=name)
        sim.step(3)
        assert sim.steps_taken == 3


def test_keyword_flags_override_the_scene(scenes):
    sim = frontier.load(scenes / "pendulum.yaml", dt=0.0025)
    assert sim.dt == 0.0025
    sim.step(4)
    assert sim.time == pytest.approx(0.01, abs=1e-15)


def test_a_load_error_is_not_a_crash_for_a_bad_urdf(tmp_path):
    path = write_scene(tmp_path, "broken.urdf", '<robot name="r">\n  <link name="a">\n</robot>\n')
    with pytest.raises(frontier.LoadError) as caught:
        frontier.load(path)
    assert pathlib.Path(caught.value.file).resolve() == path.resolve()
    assert caught.value.line >= 1


def test_a_bad_actuator_name_is_an_unknown_name_error_with_a_suggestion(scenes):
    sim = frontier.load(
        scenes / "robots" / "arm6_description" / "urdf" / "arm6.urdf", fixed_base=True, hold=True
    )
    assert "elbow_joint" in sim.actuator_names
    with pytest.raises(frontier.UnknownNameError) as caught:
        sim.set_actuator_target("elbow_jiont", 0.3)
    assert isinstance(caught.value, KeyError)
    assert "elbow_jiont" in str(caught.value)
    assert "elbow_joint" in str(caught.value)  # the nearest name
    # A body's name is not an actuator's: the arm's links carry no actuator of their own name.
    with pytest.raises(frontier.UnknownNameError):
        sim.set_actuator_target("forearm_link", 0.3)
    # An index out of range is an error as well, not a write past the end.
    with pytest.raises((IndexError, frontier.UnknownNameError)):
        sim.set_actuator_target(len(sim.actuator_names), 0.3)
    # Nothing changed: a failed call leaves the model stepping as before.
    sim.step(10)
    assert np.all(np.isfinite(sim.positions))


def test_a_bad_body_name_for_a_force_is_an_unknown_name_error(scenes):
    sim = frontier.load(scenes / "pendulum.yaml")
    with pytest.raises(frontier.UnknownNameError) as caught:
        sim.apply_force("bobb", [1.0, 0.0, 0.0])
    assert "bob" in str(caught.value)


def test_a_non_finite_force_is_refused(scenes):
    sim = frontier.load(scenes / "pendulum.yaml")
    with pytest.raises(ValueError):
        sim.apply_force("bob", [float("nan"), 0.0, 0.0])
    sim.step()
    assert np.all(np.isfinite(sim.positions))
