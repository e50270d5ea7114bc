"""A sparkling test scene and the sparkle measure, shared by tests/test_sparkle_cells.py and
bench/sparkles.py."""

import math

import bpy
import numpy as np

from . import readback, scenes

SPARKLE_BAR = 4.0  # a sparkle pixel: over this many times the median of the 5x5 around it


def sparkling_sand(sandscape, resolution, filtered=True, samples=16, seed=0, shade_left=False):
    """Sand on a wide plane under a 30 degree sun ahead, seen from 1.6 m looking down 20 degrees
    toward it: grains of 4 cm span several pixels near the camera and a fraction far away.
    The pixel filter is the sharp one (half a pixel, the preset operator's option).
    filtered=False drops the glints' pixel footprint (one cell per grain); shade_left puts a roof
    high over x < 0, hidden from the camera, so the left half of the frame lies in its shadow.
    Returns the scene."""
    bpy.ops.mesh.primitive_plane_add(size=200)
    ground = bpy.context.active_object
    settings = bpy.context.scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth, settings.density = math.radians(30), 0.0, 0.0
    settings.use_haze, settings.set_exposure = False, False
    bpy.ops.sandscape.add_atmosphere()
    scene = readback.cycles_scene(resolution=resolution, samples=samples)
    scene.cycles.seed = seed
    scene.cycles.filter_width = sandscape.addon.presets.SHARP_FILTER["filter_width"]
    scenes.camera("PERSP", location=(0.0, -30.0, 1.6), rotation=(math.radians(70), 0.0, 0.0))
    if shade_left:
        bpy.ops.mesh.primitive_plane_add(size=1, location=(-50.5, 0.0, 6.0))
        roof = bpy.context.active_object
        roof.scale = (100.0, 400.0, 1.0)
        roof.visible_camera = False
    bpy.context.view_layer.objects.active = ground
    bpy.ops.sandscape.add_sand_material(ripples=False, threshold=0.9, glint_size=0.04, facing_power=4.0)
    if not filtered:
        node = sandscape.addon.sand.glint_node(ground.active_material)
        for name in ("Pixel Angle", "Pixel Size"):
            node.inputs[name].driver_remove("default_value")
            node.inputs[name].default_value = 0.0
    return scene


def sparkle_pixels(pixels, bar=SPARKLE_BAR):
    level = pixels[..., :3].mean(-1)
    windows = np.lib.stride_tricks.sliding_window_view(np.pad(level, 2, mode="edge"), (5, 5))
    return level > bar * np.median(windows, axis=(-1, -2))


def sparkle_sizes(pixels, bar=SPARKLE_BAR):
    """Sparkle pixels grouped 8-connected: the number of pixels of each sparkle."""
    bright = sparkle_pixels(pixels, bar)
    seen, sizes = np.zeros_like(bright), []
    for start in zip(*np.nonzero(bright), strict=True):
        if seen[start]:
            continue
        stack, size = [start], 0
        seen[start] = True
        while stack:
            y, x = stack.pop()
            size += 1
            for dy in (-1, 0, 1):
                for dx in (-1, 0, 1):
                    q = (y + dy, x + dx)
                    inside = 0 <= q[0] < bright.shape[0] and 0 <= q[1] < bright.shape[1]
                    if inside and bright[q] and not seen[q]:
                        seen[q] = True
                        stack.append(q)
        sizes.append(size)
    return np.array(sizes)
