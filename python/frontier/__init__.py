"""Frontier: articulated rigid bodies with exact joints, stepped from Python.

    import frontier
    sim = frontier.load("scenes/falling_doll.yaml")   # as `frontier run` loads it
    for _ in range(1000):
        sim.step()
        z = sim.positions[:, 2]                       # (n,) metres

Units are SI throughout: metres, seconds, kilograms, radians, newtons. Orientations are unit
quaternions (w, x, y, z), body to world, as in the trajectory CSV. See help(frontier.Simulator).
"""

import os as _os

from ._errors import LoadError, SimulationError, UnknownNameError
from ._frontier import Recording, Simulator, State, __version__, read_png, write_png
from ._frontier import load as _load


def load(path, *, fixed_base=False, free_base=False, drop_height=None, hold=False, package_path=(),
         joint_positions=None, self_collision=None, dt=None, integrator=None, solver=None,
         pgs_iterations=None, keyframe=None):
    if isinstance(package_path, (str, bytes, _os.PathLike)):
        package_path = [package_path]
    return _load(_os.fspath(path), fixed_base=fixed_base, free_base=free_base, drop_height=drop_height,
                 hold=hold, package_path=[_os.fspath(p) for p in package_path],
                 joint_positions=dict(joint_positions or {}), self_collision=self_collision, dt=dt,
                 integrator=integrator, solver=solver, pgs_iterations=pgs_iterations, keyframe=keyframe)


load.__doc__ = _load.__doc__.split("\n\n", 1)[1] if "\n\n" in _load.__doc__ else _load.__doc__

__all__ = [
    "load",
    "Simulator",
    "State",
    "Recording",
    "LoadError",
    "SimulationError",
    "UnknownNameError",
    "read_png",
    "write_png",
    "__version__",
]
