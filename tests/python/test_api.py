"""The module's surface: the names users and tests rely on exist and explain themselves (help())."""
import frontier
import pytest

EXCEPTIONS = {"LoadError": ValueError, "SimulationError": RuntimeError, "UnknownNameError": KeyError}
MEMBERS = ["step", "time", "dt", "steps_taken", "gravity", "body_names", "is_static", "joint_names",
           "actuator_names", "coordinate_names", "positions", "orientations", "velocities",
           "angular_velocities", "joint_positions", "joint_velocities", "contacts", "joint_wrenches",
           "actuator_efforts", "set_actuator_target", "set_actuator_targets", "apply_force", "get_state",
           "set_state", "energy", "joint_error", "render", "record"]
# What each member's help must name: its units or layout.
UNITS = {"time": "s", "dt": "s", "gravity": "m/s", "positions": "m", "velocities": "m/s",
         "angular_velocities": "rad/s", "orientations": "w", "joint_wrenches": "N m", "energy": "J",
         "apply_force": "N", "render": "uint8"}


@pytest.mark.parametrize("name,base", sorted(EXCEPTIONS.items()))
def test_exceptions(name, base):
    assert issubclass(getattr(frontier, name), base)


def test_load_explains_itself():
    assert "fixed_base" in frontier.load.__doc__ and "LoadError" in frontier.load.__doc__


@pytest.mark.parametrize("name", MEMBERS)
def test_every_member_exists_and_has_help(name):
    member = getattr(frontier.Simulator, name)
    doc = member.__doc__ or ""
    assert len(doc.strip()) >= 10, "%s has no help" % name
    if name in UNITS:
        assert UNITS[name] in doc, "the help of %s does not give its units (%s)" % (name, UNITS[name])
