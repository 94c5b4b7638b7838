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


def load(path, **options):
    return _load(_os.fspath(path), **_paths(options))


load.__doc__ = _load.__doc__


def _paths(options):
    """Path-like keyword values (pathlib.Path) as the strings the C++ part takes."""
    if "package_path" in options:
        entries = options["package_path"]
        if isinstance(entries, (str, bytes, _os.PathLike)):
            entries = [entries]
        options["package_path"] = [_os.fspath(p) for p in entries]
    return options

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
