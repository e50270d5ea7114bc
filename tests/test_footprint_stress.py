"""Stress: 100,000 prints, a stride shorter than the foot, resolutions 1 and 16384.

Each run must finish, leave no NaN or Inf in the print map, keep heights within the
deepest print and the highest rim, and report the map's memory.
"""

import types

import bpy
import numpy as np
import pytest

from core import sole as soles
from devtools import scenes

pytestmark = pytest.mark.stress  # make stress, not make test


def paint_and_report(settings):
    """Run the paint operator's execute and return its reports and the print map's pixels."""
    reports = []
    cls = bpy.types.SANDSCAPE_OT_paint_footprints
    fake = types.SimpleNamespace(report=lambda kind, text: reports.append((kind, text)))
    fake.run = types.MethodType(cls.run, fake)
    fake.summary = types.MethodType(cls.summary, fake)
    assert cls.execute(fake, bpy.context) == {"FINISHED"}, reports
    image = next(i for i in bpy.data.images if i.get("sandscape_image") == "print_map")
    pixels = np.empty(image.size[0] * image.size[1] * 4, np.float32)
    image.pixels.foreach_get(pixels)
    return reports[-1][1], image, pixels.reshape(image.size[1], image.size[0], 4)


def check_bounded(pixels, settings):
    assert np.isfinite(pixels).all()
    top = 1.0 + settings.variation  # the largest depth scale
    # A crumbled rim's lumps rise up to RIM_LUMPS over the set rim (its mean height).
    assert pixels[..., 0].max() <= top + 1e-6 and pixels[..., 1].max() <= top * (1.0 + soles.RIM_LUMPS) + 1e-6
    assert pixels[..., :3].min() >= 0.0 and pixels[..., 2].max() <= 1.0


def walk(length, frames, terrain_size, **values):
    terrain = scenes.height_field(terrain_size, 24, name="Sand")
    walker = scenes.keyframed_walker(
        lambda f: (-length / 2 + length * (f - 1) / (frames - 1), 0.0, 0.0), range(1, frames + 1))
    return scenes.footprint_settings(terrain, walker, (1, frames), **values)


def test_a_hundred_thousand_prints():
    settings = walk(100.0, 101, 120.0, stride=0.001, resolution=2048)
    report, image, pixels = paint_and_report(settings)
    expected = int(100.0 / settings.stride) + 1  # the stride is stored as float32: 0.0010000000475
    assert expected >= 100_000 and f"Painted {expected} prints" in report and "MiB in memory" in report
    check_bounded(pixels, settings)


def test_stride_shorter_than_the_foot():
    settings = walk(3.0, 31, 6.0, stride=0.05, resolution=1024)
    report, image, pixels = paint_and_report(settings)
    assert "Painted 61 prints" in report
    check_bounded(pixels, settings)
    assert pixels[..., 0].max() > 0.5


@pytest.mark.parametrize("resolution", [1, 16384])
def test_extreme_resolutions(resolution):
    # Few prints: the map's size is under test (16384 x 3900 texels over this walk), not the
    # prints' count (31 of them spent 16 s stamping; three fill the same map).
    settings = walk(3.0, 31, 6.0, stride=1.4, resolution=resolution)
    report, image, pixels = paint_and_report(settings)
    assert image.size[0] == resolution and image.size[1] >= resolution // 5 and "MiB in memory" in report
    check_bounded(pixels, settings)
