"""Shared set-up of the Python module's tests.

The module is found in BUILD/python and the command-line program in BUILD/app/frontier, where BUILD
is the environment variable FRONTIER_BUILD (default: the `build` folder at the repository's root):

    FRONTIER_BUILD=/path/to/build /usr/bin/python3 -m pytest tests/python -q

Every test writes only into its own tmp_path, so the tests run in any order and beside others.
"""
import os
import pathlib
import subprocess
import sys

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("FRONTIER_BUILD", str(REPO / "build"))).resolve()
PYTHON_DIR = BUILD / "python"
FRONTIER_EXE = BUILD / "app" / "frontier"

sys.path.insert(0, str(PYTHON_DIR))


def pytest_configure(config):
    if not (PYTHON_DIR / "frontier").is_dir():
        raise pytest.UsageError(
            "the frontier Python module is not built in %s (set FRONTIER_BUILD to the build folder "
            "of a tree configured with -DFRONTIER_PYTHON=ON)" % PYTHON_DIR
        )


@pytest.fixture(scope="session")
def repo():
    """The repository's root (its scenes/ folder holds the bundled scenes)."""
    return REPO


@pytest.fixture(scope="session")
def scenes():
    return REPO / "scenes"


@pytest.fixture(scope="session")
def here():
    """This folder: the scenes written for these tests."""
    return pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="session")
def frontier_cli():
    """Runs the `frontier` program with the given arguments; returns the CompletedProcess."""
    if not FRONTIER_EXE.is_file():
        pytest.fail("the frontier program is not built: %s" % FRONTIER_EXE)

    def run(*args, timeout=600):
        return subprocess.run(
            [str(FRONTIER_EXE), *map(str, args)],
            capture_output=True,
            text=True,
            timeout=timeout,
        )

    return run
