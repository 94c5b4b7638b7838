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
    """The pixels of an 8-bit RGB or RGBA PNG without interlacing (what the renderer writes) as an
    (h, w, 3) uint8 array; a reader of our own, so that no imaging package is needed."""
    import struct
    import zlib

    import numpy as np

    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG: %s" % path
    offset, idat = 8, b""
    while offset < len(data):
        length, kind = struct.unpack(">I4s", data[offset:offset + 8])
        body = data[offset + 8:offset + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, (depth, colour, interlace)
        elif kind == b"IDAT":
            idat += body
        offset += 12 + length
    channels = 3 if colour == 2 else 4
    stride = width * channels
    raw = zlib.decompress(idat)
    out = np.zeros((height, stride), dtype=np.int32)
    previous = np.zeros(stride, dtype=np.int32)
    for y in range(height):
        start = y * (stride + 1)
        kind = raw[start]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=start + 1).astype(np.int32)
        if kind == 0:
            row = line
        elif kind == 2:
            row = (line + previous) & 0xFF
        else:  # Sub, Average and Paeth depend on the pixel to the left: per byte
            row = np.zeros(stride, dtype=np.int32)
            for x in range(stride):
                left = row[x - channels] if x >= channels else 0
                up = previous[x]
                up_left = previous[x - channels] if x >= channels else 0
                if kind == 1:
                    predictor = left
                elif kind == 3:
                    predictor = (left + up) // 2
                else:
                    p = left + up - up_left
                    pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                    predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else up_left)
                row[x] = (line[x] + predictor) & 0xFF
        out[y] = row
        previous = row
    return out.reshape(height, width, channels)[:, :, :3].astype(np.uint8)
