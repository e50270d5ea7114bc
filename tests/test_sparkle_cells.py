"""Sparkles as pinpoints: glint cells sized to the pixel's footprint (Sandscape Glint Cells).

The twin's promises (a fine cell sparkles as often per area as a grain; a coarse one carries
its grains' mean light), the group against the twin (bakes), and renders: a sparkle covers about
one pixel at any resolution, where a grain wider than a pixel made a block before.
"""

import math

import bpy
import numpy as np
import pytest

from core import glints as twin
from devtools import readback, scenes, sparkles

SIZE, THRESHOLD = 1 / 16, 0.9
SKY_MIRROR = 2.5
PINPOINT = 1.5  # pixels per sparkle on average (the pixel filter spreads a point over up to four)


def plane_points(res, size):
    c = readback.pixel_centres(res, -size / 2, size / 2)
    x, y = np.meshgrid(c, c)
    return np.stack([x, y, np.zeros_like(x)], axis=-1)


# ---------------------------------------------------------------- twin

@pytest.mark.parametrize("level", [-3, -2, -1, 0])
def test_fine_cells_sparkle_as_often_per_area_as_grains(level):
    """Cells finer than a grain: as many sparkling cells per square metre as sparkling grains,
    each as bright in its pixel as a grain covering that pixel."""
    grain, res = 0.01, 500  # 500 x 500 cells of the level
    footprint = grain * 2.0 ** level / twin.SPARKLE_CELL * 0.99  # just inside the level
    assert twin.sparkle_level(footprint, grain) == level
    cell = grain * 2.0 ** level
    span = res * cell
    points = plane_points(res, span)  # one point per cell
    noise, _, threshold, weight = twin.sparkle_noise(points, footprint, grain, THRESHOLD, seed=4)
    count = int((noise > threshold).sum())
    expected = (1 - THRESHOLD) * (span / grain) ** 2
    sigma = math.sqrt(expected)
    print(f"level {level}: {count} sparkles, expected {expected:.0f} ± {sigma:.0f}")
    assert abs(count - expected) <= 3 * sigma + 0.01 * expected  # 4^level(1-t) ≈ 1 - t^(4^level)
    # Its pixel holds the grain's light, at most a whole pixel of mirror (face on: N.V = 1).
    assert np.allclose(weight * cell**2 / footprint**2, min(1.0, grain**2 / footprint**2), rtol=1e-5)


@pytest.mark.parametrize("level", [1, 2, 4])
def test_coarse_cells_keep_the_mean_glint_light(level):
    grain = 0.01
    footprint = grain * 2.0 ** level / twin.SPARKLE_CELL * 0.99
    cell = grain * 2.0 ** level
    points = plane_points(200, 200 * cell)
    noise, _, threshold, weight = twin.sparkle_noise(points, footprint, grain, THRESHOLD, seed=7)
    light = (noise > threshold) * weight
    p = 1 - THRESHOLD ** 4.0 ** level
    sigma = weight.flat[0] * math.sqrt(p * (1 - p) / light.size)
    print(f"level {level}: mean {light.mean():.4f}, expected {1 - THRESHOLD} ± {sigma:.4f}")
    assert abs(light.mean() - (1 - THRESHOLD)) <= 3 * sigma + 1e-6


def test_no_footprint_is_one_cell_per_grain():
    points = plane_points(64, 2.0)
    noise, tilt, threshold, weight = twin.sparkle_noise(points, 0.0, SIZE, THRESHOLD, seed=3)
    assert np.array_equal(noise, twin.cell_noise(points, SIZE, 3))
    assert np.all(threshold == np.float32(THRESHOLD)) and np.all(weight == 1.0)


# ---------------------------------------------------------------- bakes

@pytest.mark.parametrize("pixel_size", [0.0, 0.004, 0.03, 0.11, 0.9])
def test_the_group_picks_the_twins_cells(sandscape, pixel_size):
    """Pixel Size (the orthographic footprint) sets one level per bake; every output as the twin."""
    group = sandscape.node_groups.helper.ensure_group(sandscape.node_groups.glint_cells)
    values = {"Glint Size": SIZE, "Seed": 2.0, "Threshold": THRESHOLD, "Pixel Size": pixel_size}
    plane = readback.uv_plane(2.0)
    baked = {}
    for output in ("Noise", "Threshold", "Weight", "Cell Size"):
        material = scenes.group_material(group, values, output)
        plane.data.materials.clear()
        plane.data.materials.append(material)
        baked[output] = readback.bake_emit(plane, material, 64)[..., 0]
    noise, _, threshold, weight = twin.sparkle_noise(plane_points(64, 2.0), pixel_size, SIZE, THRESHOLD, 2)
    cell_size, _, _ = twin.sparkle_cells(pixel_size, SIZE, THRESHOLD)
    assert np.allclose(baked["Threshold"], threshold, rtol=1e-5, atol=1e-6)
    assert np.allclose(baked["Weight"], weight, rtol=1e-5, atol=1e-6)
    assert np.allclose(baked["Cell Size"], cell_size, rtol=1e-6)
    assert np.mean(np.abs(baked["Noise"] - noise) < 1e-6) >= 0.999  # a cell edge on a bake point may flip


# ---------------------------------------------------------------- renders

@pytest.mark.parametrize("resolution", [(160, 90), (320, 180)])
def test_a_sparkle_covers_about_one_pixel(sandscape, resolution):
    sizes = sparkles.sparkle_sizes(readback.render(sparkles.sparkling_sand(sandscape, resolution)))
    print(f"{resolution}: {sizes.size} sparkles, {sizes.mean():.2f} px each, largest {sizes.max()}")
    assert sizes.size >= 40
    assert sizes.mean() <= PINPOINT and np.mean(sizes >= 4) <= 0.05  # noise joins a neighbour or two


def test_without_the_footprint_grains_make_blocks(sandscape):
    """The same sand with Pixel Angle 0 (one cell per grain) fails the bar above: near grains
    span several pixels."""
    sizes = sparkles.sparkle_sizes(readback.render(sparkles.sparkling_sand(sandscape, (320, 180), False)))
    print(f"unfiltered: {sizes.size} sparkles, {sizes.mean():.2f} px each, largest {sizes.max()}")
    assert sizes.mean() >= PINPOINT + 0.3 and np.mean(sizes >= 4) > 0.05


def test_in_shade_a_facet_mirrors_the_sky_no_brighter_than_sunlit_sand(sandscape):
    """A grain's light carried into one pixel must not make stars of the facets that mirror the
    sky: in the roof's shadow no pixel is more than SKY_MIRROR times the sunlit sand's median (a
    facet mirroring the bright sky round the sun), where the sun's glints reach 7-20 times it."""
    # 64 samples: a sub-pixel sparkle's pixel is an estimate, and its noise must not make the star.
    scene = sparkles.sparkling_sand(sandscape, (160, 90), samples=64, shade_left=True)
    pixels = readback.render(scene)
    level = pixels[..., :3].mean(-1)
    shaded, sunlit = level[:, 2:37], level[:, 100:]  # the shadow edge runs from column 45 to 68
    print(f"shade: brightest {shaded.max():.3f}, median {np.median(shaded):.3f}; sunlit median "
          f"{np.median(sunlit):.3f}, brightest {sunlit.max():.3f}")
    assert sunlit.max() >= 2 * shaded.max()  # the sun's glints outshine the sky's
    assert shaded.max() <= SKY_MIRROR * np.median(sunlit)


def test_sand_made_before_the_camera_follows_the_camera_added_after(sandscape):
    """Blender skips a driver that failed once (no camera yet) until the file is reloaded: the
    sparkle drivers are re-armed when the scene gets its camera, and follow a lens change."""
    bpy.ops.mesh.primitive_plane_add(size=10)
    ground = bpy.context.active_object
    assert bpy.context.scene.camera is None
    assert bpy.ops.sandscape.add_sand_material(ripples=False) == {"FINISHED"}
    bpy.context.view_layer.update()
    camera = scenes.camera("PERSP", location=(0.0, -5.0, 2.0), rotation=(math.radians(70), 0.0, 0.0))
    scene = readback.cycles_scene(resolution=(200, 100))
    bpy.context.view_layer.update()
    bpy.context.view_layer.update()  # the first update re-arms, the second evaluates
    node = sandscape.addon.sand.glint_node(ground.active_material)
    expected = sandscape.addon.sparkle_footprint.pixel_angle(scene)
    assert node.inputs["Pixel Angle"].default_value == pytest.approx(expected, rel=1e-5)
    camera.data.lens = 100.0
    bpy.context.view_layer.update()
    assert node.inputs["Pixel Angle"].default_value == pytest.approx(
        sandscape.addon.sparkle_footprint.pixel_angle(scene), rel=1e-5)
    assert sandscape.addon.sparkle_footprint.pixel_angle(scene) < expected / 1.9  # 50 mm to 100 mm
