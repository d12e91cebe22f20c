"""World.render against the command line's `graspkit render` (the same picture, pixel for pixel,
read back from its PNG by a decoder written here) and against a closed form (a box seen head-on
from its side covers the rectangle its face projects to)."""

import math
import struct
import zlib

import numpy as np
import pytest

import graspkit
from conftest import run_cli


def read_png(path):
    """An 8-bit RGB, non-interlaced PNG as a (height, width, 3) array: the five row filters."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat, width, height = 8, b"", 0, 0
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, colour, interlace) == (8, 2, 0)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    raw = zlib.decompress(idat)
    stride = width * 3
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b = previous[i]
            c = previous[i - 3] if i >= 3 else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, 3)


def test_render_equals_the_command_line(graspit_data, graspkit_exe, tmp_path):
    world_file = graspit_data / "worlds" / "plannerMug.xml"
    world = graspkit.load_world(world_file)
    pixels = world.render(width=160, height=120, camera="iso", contacts=True,
                          out=tmp_path / "py.png")
    assert pixels.shape == (120, 160, 3) and pixels.dtype == np.uint8
    run_cli(graspkit_exe, "render", str(world_file), "--out", str(tmp_path / "cli.png"),
            "--size", "160x120", "--camera", "iso", "--contacts",
            # World.render draws the world as it is: no floor, a solid hand, the files' colours.
            "--no-floor", "--hand", "solid", "--file-colours")
    np.testing.assert_array_equal(read_png(tmp_path / "cli.png"), pixels)
    np.testing.assert_array_equal(read_png(tmp_path / "py.png"), pixels)


def test_box_face_is_the_projected_rectangle(models):
    # models/objects/box.iv: 60 x 60 x 120 mm about its origin. Seen from +x ("+x" frames it),
    # the face x = 30 shows 60 (y) wide and 120 (z) high.
    world = graspkit.World()
    world.add_object(models / "objects/box.xml")
    pixels = world.render(width=200, height=200, camera="+x")
    covered = np.any(pixels < 250, axis=2)
    rows = np.nonzero(covered.any(axis=1))[0]
    cols = np.nonzero(covered.any(axis=0))[0]
    height_px, width_px = rows[-1] - rows[0] + 1, cols[-1] - cols[0] + 1
    # The camera frames the box's bounding sphere (radius sqrt(30^2 + 30^2 + 60^2)) in a 45°
    # view: distance r / sin(22.5°) from the centre, so the face is that less 30 mm away.
    r = math.sqrt(30**2 + 30**2 + 60**2)
    face = r / math.sin(math.radians(22.5)) - 30
    scale = 100 / math.tan(math.radians(22.5))  # pixels per unit on the image plane
    assert height_px == pytest.approx(120 / face * scale, abs=2)
    assert width_px == pytest.approx(60 / face * scale, abs=2)


def test_render_refuses_bad_requests():
    world = graspkit.World()
    with pytest.raises(graspkit.Error, match="sideways"):
        world.render(camera="sideways")
    with pytest.raises(graspkit.Error, match="16384"):
        world.render(width=0)
