"""Helpers of the Python module's tests (plain functions; the fixtures are in conftest.py)."""
import pathlib


def write_scene(folder, name, text):
    """Writes a scene's YAML text to folder/name; returns the path (for tests of small scenes)."""
    path = pathlib.Path(folder) / name
    path.write_text(text)
    return path


def read_trajectory(path):
    """The rows of a trajectory CSV (docs/files.md) as {time: {body: [13 floats]}}; the comment line
    is skipped. Python's float() reads the 17 significant digits back bit for bit."""
    rows = {}
    with open(path) as f:
        header = None
        for line in f:
            if line.startswith("#"):
                continue
            fields = line.rstrip("\n").split(",")
            if header is None:
                header = fields
                assert header == "time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz".split(",")
                continue
            rows.setdefault(float(fields[0]), {})[fields[1]] = [float(v) for v in fields[2:]]
    return rows


def read_png(path):
    """The pixels of a PNG file as an (h, w, 3) uint8 array (libpng, through the module)."""
    import frontier

    return frontier.read_png(path)
