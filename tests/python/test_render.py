"""sim.render: an (h, w, 3) uint8 image of the scene from the same OSMesa renderer as the command
line's frames."""
import frontier
import numpy as np
import pytest


def distinct_colours(image):
    return len(np.unique(image.reshape(-1, 3), axis=0))


def test_a_render_of_the_falling_doll_is_not_blank(scenes):
    sim = frontier.load(scenes / "falling_doll.yaml")
    sim.step(300)
    image = sim.render()
    assert isinstance(image, np.ndarray)
    assert image.shape == (480, 640, 3)
    assert image.dtype == np.uint8
    assert image.flags["C_CONTIGUOUS"]
    # Many colours (the doll's shaded boxes, the floor, the sky), and the commonest of them (the
    # background) covers well under the whole frame.
    assert distinct_colours(image) >= 20
    colours, counts = np.unique(image.reshape(-1, 3), axis=0, return_counts=True)
    assert counts.max() < 0.9 * image.shape[0] * image.shape[1]
    # Not a blank frame of a single colour per channel either.
    assert all(np.ptp(image[:, :, c]) > 50 for c in range(3))


def test_the_size_and_the_camera_are_as_asked(scenes):
    sim = frontier.load(scenes / "falling_doll.yaml")
    small = sim.render(width=320, height=200)
    assert small.shape == (200, 320, 3) and small.dtype == np.uint8
    default_view = sim.render(320, 200)
    assert np.array_equal(small, default_view)  # the same state renders the same frame
    # A camera looking away from the doll sees no doll: fewer colours than one looking at it.
    at = sim.render(320, 200, camera=dict(position=[0.0, -3.0, 1.2], look_at=[0.0, 0.0, 1.0], fov=40))
    away = sim.render(320, 200, camera=dict(position=[0.0, -3.0, 1.2], look_at=[0.0, -10.0, 1.2], fov=40))
    assert not np.array_equal(at, away)
    assert distinct_colours(at) > distinct_colours(away)


def test_the_doll_moves_in_the_frames(scenes):
    sim = frontier.load(scenes / "falling_doll.yaml")
    first = sim.render(320, 240)
    sim.step(600)
    second = sim.render(320, 240)
    changed = np.any(first != second, axis=2).mean()
    assert changed > 0.01  # a visible part of the frame changed as the doll fell


def test_bad_sizes_are_refused(scenes):
    sim = frontier.load(scenes / "pendulum.yaml")
    for width, height in ((0, 480), (640, 0), (-5, 10)):
        with pytest.raises(ValueError):
            sim.render(width, height)
